#!/usr/bin/env bash
# vri-render --early-termination auto: the stats say how many rays ended early and the most they left
# out, below the bound; the image is within that of the image without termination (tests/unit/
# early_termination_test.cpp covers every integrator, precision and emission model).
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
bin=${VRI_BIN:?}
source "$(dirname "${BASH_SOURCE[0]}")/lib/blob.sh" && write_blob_volume
cat > opaque.yaml <<'YAML'
points:
  - [0.0, 0.0, 0.0, 0.0, 0.0]
  - [0.3, 0.0, 0.0, 0.0, 0.0]
  - [0.7, 1.0, 0.5, 0.2, 2.0]
  - [1.0, 1.0, 1.0, 1.0, 4.0]
YAML
render() { "$bin/vri-render" --volume blob_8x8x8_uint8.raw --tf opaque.yaml --size 37x29 --eye 20,15,-12 --step 0.4 -q "$@"; }

render -o off.exr --stats off.json
render --early-termination auto:1e-3 -o auto.exr --stats auto.json
render --early-termination auto -o default.exr --stats default.json
"$bin/vri-diff" off.exr auto.exr --json diff.json > /dev/null || true
python3 - <<'PY' || fail "stats JSON"
import json
off, auto, default, diff = (json.load(open(f)) for f in ("off.json", "auto.json", "default.json", "diff.json"))
assert off["stats"]["rays_terminated"] == 0 and off["stats"]["termination_left_out_max"] == 0, "off"
assert auto["options"]["early_termination"] == {"bound": 1e-3}, auto["options"]["early_termination"]
assert default["options"]["early_termination"] == {"bound": 1e-4}, default["options"]["early_termination"]
left = auto["stats"]["termination_left_out_max"]
assert auto["stats"]["rays_terminated"] > 0 and 0 < left < 1e-3, auto["stats"]
assert auto["stats"]["samples_placed"] < off["stats"]["samples_placed"], "samples"
largest = max(c["max_abs"] for c in diff["channels"])
assert 0 < largest <= left + 1e-6, (largest, left)  # + the EXR's float rounding
assert default["stats"]["termination_left_out_max"] < 1e-4, "default bound"
PY
echo "early termination: auto ends $(python3 -c 'import json;print(json.load(open("auto.json"))["stats"]["rays_terminated"])') rays within its bound"
