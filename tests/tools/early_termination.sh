#!/usr/bin/env bash
# vri-render --early-termination auto: the stats say how many rays ended early and the most they left
# out, below the bound; the image is within that of the image without termination (tests/unit/
# early_termination_test.cpp covers every integrator, precision and emission model), for every method,
# on the blob under an opaque transfer function and on Neghip and Bonsai where the data are at hand.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
bin=${VRI_BIN:?} src=${VRI_SOURCE:?}
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
/usr/bin/python3 - <<'PY' || fail "stats JSON"
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
echo "early termination: auto ends $(/usr/bin/python3 -c 'import json;print(json.load(open("auto.json"))["stats"]["rays_terminated"])') rays within its bound"

# Every method that takes `auto`, with and without it: each pixel-channel within the stats' largest
# left-out amount, which stays below B, plus the EXR's float32 rounding of the two values (half an ulp
# each: 2^-24 of the largest value, which a Riemann sum at tau h = 12 takes up to 12).
# Steps of 2 voxels at an extinction up to 6 per voxel (dense.yaml) are where the Simpson methods' quadrature
# adds more than the integral's bound C_max T (before the rule covered it: up to 1.9 B on Neghip).
cat > dense.yaml <<'YAML'
points:
  - [0.0, 0.0, 0.0, 0.0, 0.0]
  - [0.2, 0.0, 0.0, 0.0, 0.0]
  - [0.25, 1.0, 1.0, 1.0, 6.0]
  - [1.0, 1.0, 1.0, 1.0, 6.0]
YAML
methods=("riemann --step 2" "composite --step 2" "simpson --step 2" "simpson --step 2 --precision float"
         "coupled --h-max 4" "decoupled --h-max 4 --accepted-value paper" "decoupled --h-max none")
within_bound() {  # within_bound NAME SCENE-ARGS...: every method at B = 1e-2 and 1e-4
  local name=$1; shift
  for method in "${methods[@]}"; do
    local tag=$name-${method//[^a-z0-9.]/}
    # shellcheck disable=SC2086
    "$bin/vri-render" "$@" --method $method -q -o "$tag.exr"
    for bound in 0.01 0.0001; do
      # shellcheck disable=SC2086
      "$bin/vri-render" "$@" --method $method --early-termination "auto:$bound" -q -o "$tag-$bound.exr" \
        --stats "$tag-$bound.json"
      "$bin/vri-diff" "$tag.exr" "$tag-$bound.exr" --json "$tag-$bound-diff.json" > /dev/null || true
      /usr/bin/python3 - "$tag-$bound" "$bound" <<'PY' || fail "$name, $method, auto:$bound"
import json, sys
tag, bound = sys.argv[1], float(sys.argv[2])
stats = json.load(open(tag + ".json"))["stats"]
largest = max(c["max_abs"] for c in json.load(open(tag + "-diff.json"))["channels"])
left = stats["termination_left_out_max"]
rounding = 2.0 ** -23 * max(1.0, stats["out_of_range_pixels"]["max"])
assert left < bound, (left, bound)
assert largest <= left + rounding, ("changed by", largest, "left out at most", left, "rounding", rounding)
print(f"{tag}: {stats['rays_terminated']} rays ended, changed by {largest:.3g} <= {left:.3g} < {bound}")
PY
    done
  done
}
within_bound blob --volume blob_8x8x8_uint8.raw --tf opaque.yaml --size 37x29 --eye 20,15,-12
data=${VRI_DATA_DIR:-$src/../shared/data/volumes}
if [[ -f $data/neghip_64x64x64_uint8.raw && -f $data/bonsai_256x256x256_uint8.raw ]]; then
  within_bound neghip --volume "$data/neghip_64x64x64_uint8.raw" --tf dense.yaml --size 48x48
  within_bound bonsai --volume "$data/bonsai_256x256x256_uint8.raw" --tf "$src/experiments/tf/paper-b-bonsai.yaml" \
    --size 64x48
else
  echo "no Neghip or Bonsai in $data: the methods checked on the blob only"
fi
