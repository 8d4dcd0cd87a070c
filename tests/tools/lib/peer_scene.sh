# Sourced by the peer tests (peers.sh, peers_web.sh): write_peer_scene writes, into the current directory,
# vol_12x12x12_uint8.raw, a small asymmetric volume (zero on its faces, an off-centre blob on a ramp), the same
# volume flipped in y as flip_12x12x12_uint8.raw (a scene-match mistake to tell apart), and tf.yaml.
write_peer_scene() {
  /usr/bin/python3 - <<'PY'
import numpy as np
n = 12
z, y, x = np.meshgrid(np.arange(n), np.arange(n), np.arange(n), indexing="ij")
v = 40 + 12 * y + 6 * x + 80 * np.exp(-((x - 7.5) ** 2 + (y - 8) ** 2 + (z - 5) ** 2) / 6.0)
v[[0, -1], :, :] = v[:, [0, -1], :] = v[:, :, [0, -1]] = 0
v = np.clip(np.round(v), 0, 255).astype(np.uint8)
v.tofile("vol_12x12x12_uint8.raw")
v[:, ::-1, :].tofile("flip_12x12x12_uint8.raw")
PY
  cat > tf.yaml <<'YAML'
points:
  - [0.0, 0.0, 0.0, 0.0, 0.0]
  - [0.1, 0.0, 0.0, 0.0, 0.0]
  - [0.4, 0.9, 0.4, 0.1, 0.08]
  - [0.7, 0.3, 0.6, 1.0, 0.3]
  - [1.0, 1.0, 1.0, 1.0, 0.5]
YAML
}
