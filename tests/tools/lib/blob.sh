# Sourced by the tool tests that render: writes blob_8x8x8_uint8.raw, a deterministic 8x8x8 uint8
# volume (a ramp with some structure), into the current directory.
write_blob_volume() {
  for i in $(seq 0 511); do printf "\\x$(printf %02x $(( (i * 37 + i / 64 * 11) % 256 )))"; done > blob_8x8x8_uint8.raw
}
