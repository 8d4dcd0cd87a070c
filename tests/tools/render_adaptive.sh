#!/usr/bin/env bash
# vri-render's paper B methods end to end: coupled and decoupled with their counts in the stats, the
# per-ray log as CSV, uniform Simpson, bitwise neutral empty-space skipping, and bad adaptive options.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"

# A deterministic 8x8x8 uint8 volume and a transfer function with an empty range.
source "$(dirname "${BASH_SOURCE[0]}")/lib/blob.sh" && write_blob_scene
render() { "$VRI_BIN/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 40x30 -q "$@"; }
count() { grep -o "\"$2\": [0-9]*" "$1" | head -1 | grep -o '[0-9]*$'; }  # count FILE KEY: an integer of the stats

render --method coupled --tolerance 0.001 --log-ray 20,15 --log ray.csv -o c.exr --stats c.json
grep -q '"tolerance": 0.001' c.json
[ "$(count c.json outer_steps)" -gt 0 ] || fail "no outer steps"
[ "$(count c.json inner_tries)" -ge "$(count c.json outer_steps)" ] || fail "fewer inner tries than outer steps"
head -1 ray.csv | grep -q '^kind,accepted,skipped,t,h,t_end,error,tolerance,r,g,b,alpha,transparency$'
grep -q '^outer,1,' ray.csv
# Steps within [h_min, h_max] = [0.1, 2] (the last piece of a ray, inner and outer, may be shorter).
awk -F, 'NR > 1 && $5 > 2 { exit 1 }' ray.csv || fail "a step above h_max"
[ "$(awk -F, 'NR > 1 && $5 < 0.1 - 1e-12' ray.csv | wc -l)" -le 2 ] || fail "steps below h_min"

render --method decoupled --h-max none --accepted-value paper -o d.exr --stats d.json
grep -q '"h_max_voxels": "none"' d.json
grep -q '"accepted_value": "paper"' d.json

# Skipping empty space changes no bit; uniform Simpson takes no adaptive decision.
render --method coupled --tolerance 0.001 --no-skip-empty -o c2.exr
"$VRI_BIN/vri-diff" c.exr c2.exr --fail 0 > /dev/null
render --method simpson --step 0.25 -o s.exr --stats s.json
[ "$(count s.json inner_failures)" -eq 0 ] && [ "$(count s.json outer_failures)" -eq 0 ] || fail "uniform Simpson failed a try"

expect_error() {  # expect_error PATTERN ARGS...
  local pattern=$1; shift
  set +e; "$VRI_BIN/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 40x30 "$@" -o bad.exr -q 2> err.txt
  local rc=$?; set -e
  [ "$rc" -ne 0 ] || { echo "expected failure for: $*"; exit 1; }
  [ "$(wc -l < err.txt)" -eq 1 ] || { echo "expected one line for: $*"; cat err.txt; exit 1; }
  grep -q -- "$pattern" err.txt || { echo "expected '$pattern' for: $*"; cat err.txt; exit 1; }
  if ls bad.* > /dev/null 2>&1; then echo "output written despite failure: $*"; exit 1; fi
}
expect_error "--h-min" --method coupled --h-min 0
expect_error "h_max" --method coupled --h-max 0.2
expect_error "--h-max" --method coupled --h-max lots
expect_error "tolerance" --method coupled --tolerance -1
expect_error "--accepted-value" --method coupled --accepted-value boole
expect_error "--log-ray" --method coupled --log-ray 1,2,3 --log x.csv
expect_error "outside" --method coupled --log-ray 40,0 --log x.csv
expect_error "--log" --method coupled --log x.csv
expect_error "unknown method" --method trapezoid
echo ok
