# Sourced by the tool tests that render: write_blob_scene writes, into the current directory,
# blob_8x8x8_uint8.raw, a deterministic 8x8x8 uint8 volume (a ramp with some structure), and tf.yaml,
# a transfer function that hides the low values (so that empty space is skipped) and shows the rest.
write_blob_volume() {
  for i in $(seq 0 511); do printf "\\x$(printf %02x $(( (i * 37 + i / 64 * 11) % 256 )))"; done > blob_8x8x8_uint8.raw
}
write_blob_scene() {
  write_blob_volume
  cat > tf.yaml <<'YAML'
points:
  - [0.0, 0.0, 0.0, 0.0, 0.0]
  - [0.3, 0.0, 0.0, 0.0, 0.0]
  - [0.7, 1.0, 0.5, 0.2, 0.4]
  - [1.0, 1.0, 1.0, 1.0, 0.8]
YAML
}
