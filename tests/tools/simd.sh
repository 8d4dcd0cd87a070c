#!/usr/bin/env bash
# vri-render --simd: the packet engine's float image equals the scalar path's bit for bit end to end
# (tests/unit/simd_march_test.cpp covers every combination), and the stats say which path ran.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
bin=${VRI_BIN:?}
source "$(dirname "${BASH_SOURCE[0]}")/lib/blob.sh" && write_blob_scene
render() { "$bin/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 41x29 --precision float -q "$@"; }

for run in "riemann entry" "composite eye --no-skip-empty" "riemann entry-exit-corner --threads 1"; do
  set -- $run
  method=$1 placement=$2
  shift 2
  render --method "$method" --placement "$placement" "$@" --step 0.3 --simd on -o on.exr --stats on.json
  render --method "$method" --placement "$placement" "$@" --step 0.3 --simd off -o off.exr --stats off.json
  "$bin/vri-diff" on.exr off.exr --fail 0 > /dev/null || fail "$run: --simd on and off differ"
done
"$bin/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 41x29 -q -o double.exr --stats double.json
# Frames after the first reuse its empty-space grid (occupancy_cache.h): the record says so and still
# gives the grid's build time, outside the frame's wall time.
render --step 0.3 -o once.exr --stats once.json
render --step 0.3 --warm-up 1 --repeat 2 -o warm.exr --stats warm.json
"$bin/vri-diff" warm.exr once.exr --fail 0 > /dev/null || fail "--warm-up: the image changed"

# Every SIMD target this host has, forced by --simd TARGET and by VRI_SIMD_TARGET, gives the scalar path's
# image bit for bit and is named in the stats; the machine record lists the targets and the CPU's flags.
targets=$(/usr/bin/python3 -c 'import json,sys; print(" ".join(json.load(open(sys.argv[1]))["machine"]["simd_targets"]))' on.json)
[[ -n $targets ]] || fail "machine.simd_targets is empty"
render --step 0.3 --simd off -o scalar.exr
for target in $targets; do
  render --step 0.3 --simd "$target" -o forced.exr --stats forced.json
  "$bin/vri-diff" forced.exr scalar.exr --fail 0 > /dev/null || fail "--simd $target differs from the scalar path"
  VRI_SIMD_TARGET=$target render --step 0.3 -o env.exr --stats env.json
  "$bin/vri-diff" env.exr scalar.exr --fail 0 > /dev/null || fail "VRI_SIMD_TARGET=$target differs from the scalar path"
  /usr/bin/python3 - "$target" <<'PY' || fail "stats of --simd $target"
import json, sys
target = sys.argv[1]
forced, env = json.load(open("forced.json")), json.load(open("env.json"))
assert forced["stats"]["simd_target"] == target and forced["options"]["simd_target"] == target, forced["stats"]
assert env["stats"]["simd_target"] == target and "simd_target" not in env["options"], env["stats"]
assert isinstance(forced["machine"]["cpu_simd_flags"], list), "machine.cpu_simd_flags"
# How the packets read voxels is named where it applies, AVX2, and only there.
assert ("voxel_loads" in forced["stats"]) == (target == "AVX2"), forced["stats"]
PY
  if [[ $target == AVX2 ]]; then  # either way of loading, forced, gives the same image and is named
    for loads in gather scalar; do
      VRI_VOXEL_LOADS=$loads render --step 0.3 --simd AVX2 -o loads.exr --stats loads.json
      "$bin/vri-diff" loads.exr scalar.exr --fail 0 > /dev/null || fail "VRI_VOXEL_LOADS=$loads differs from the scalar path"
      /usr/bin/python3 -c 'import json,sys; assert json.load(open("loads.json"))["stats"]["voxel_loads"] == sys.argv[1]' "$loads" ||
        fail "stats.voxel_loads of VRI_VOXEL_LOADS=$loads"
    done
  fi
done

# The exact method's batched Gauss rules (tolerance 1e-10 up) on every target: the same values and bounds
# bit for bit (exact_gauss_batch.h), and the stats name the target; below 1e-10 no batch runs.
exact() { "$bin/vri-reference" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 41x29 --tolerance 1e-7 -q "$@"; }
exact -o exact.exr --error-image exact-bound.exr --stats exact.json
for target in $targets; do
  exact --simd "$target" -o exact-forced.exr --error-image exact-forced-bound.exr --stats exact-forced.json
  "$bin/vri-diff" exact-forced.exr exact.exr --fail 0 > /dev/null || fail "exact --simd $target: the image differs"
  "$bin/vri-diff" exact-forced-bound.exr exact-bound.exr --fail 0 > /dev/null || fail "exact --simd $target: the bounds differ"
  /usr/bin/python3 - "$target" <<'PY' || fail "exact stats of --simd $target"
import json, sys
forced = json.load(open("exact-forced.json"))
assert forced["stats"]["simd_target"] == sys.argv[1] and forced["options"]["simd_target"] == sys.argv[1], forced["stats"]
PY
done
"$bin/vri-reference" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 41x29 --tolerance 1e-13 -q -o fine.exr --stats fine.json
/usr/bin/python3 - "${targets%% *}" <<'PY' || fail "exact stats"
import json, sys
best, fine = json.load(open("exact.json")), json.load(open("fine.json"))
assert best["stats"]["simd_target"] == sys.argv[1] and "simd_target" not in best["options"], best["stats"]
assert fine["stats"]["simd_target"] is None, "no Gauss batch below 1e-10"
PY

/usr/bin/python3 - <<'PY' || fail "stats JSON"
import json
on, off, double = (json.load(open(f)) for f in ("on.json", "off.json", "double.json"))
assert on["options"]["simd"] is True and off["options"]["simd"] is False, "options.simd"
assert isinstance(on["stats"]["simd_target"], str) and on["stats"]["simd_target"], "simd_target of --simd on"
assert off["stats"]["simd_target"] is None, "simd_target of --simd off"
assert double["options"]["simd"] is True and double["stats"]["simd_target"] is None, "double precision is scalar"
assert on["stats"]["samples_evaluated"] == off["stats"]["samples_evaluated"] > 0, "samples_evaluated"
once, warm = json.load(open("once.json")), json.load(open("warm.json"))
assert once["stats"]["setup_reused"] is False and on["stats"]["setup_seconds"] > 0, "the first frame builds the grid"
assert warm["stats"]["setup_reused"] is True and warm["stats"]["setup_seconds"] > 0, "a later frame reuses it"
PY
echo "simd: on, off and every target ($targets) bitwise equal, the exact method's too; stats name the target and AVX2's voxel loads; later frames reuse the grid"
