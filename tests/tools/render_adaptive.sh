#!/usr/bin/env bash
# vri-render's paper B methods end to end: coupled and decoupled with their counts in the stats, the
# per-ray log as CSV, uniform Simpson, bitwise neutral empty-space skipping, and bad adaptive options.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"

# A deterministic 8x8x8 uint8 volume and a transfer function with an empty range.
for i in $(seq 0 511); do printf "\\x$(printf %02x $(( (i * 37 + i / 64 * 11) % 256 )))"; done > blob_8x8x8_uint8.raw
cat > tf.yaml <<'YAML'
points:
  - [0.0, 0.0, 0.0, 0.0, 0.0]
  - [0.3, 0.0, 0.0, 0.0, 0.0]
  - [0.7, 1.0, 0.5, 0.2, 0.4]
  - [1.0, 1.0, 1.0, 1.0, 0.8]
YAML
render() { "$VRI_BIN/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 40x30 -q "$@"; }
json() { python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print(eval(sys.argv[2]))" "$@"; }

render --method coupled --tolerance 0.001 --log-ray 20,15 --log ray.csv -o c.exr --stats c.json
[ "$(json c.json "d['options']['tolerance']")" = 0.001 ]
[ "$(json c.json "d['stats']['adaptive']['outer_steps'] > 0")" = True ]
[ "$(json c.json "d['stats']['adaptive']['inner_tries'] >= d['stats']['adaptive']['outer_steps']")" = True ]
head -1 ray.csv | grep -q '^kind,accepted,skipped,t,h,t_end,error,tolerance,r,g,b,alpha,transparency$'
grep -q '^outer,1,' ray.csv
# Steps within [h_min, h_max] = [0.1, 2] (the last piece of a ray may be shorter).
python3 - <<'PY'
import csv
rows = list(csv.DictReader(open("ray.csv")))
assert rows, "empty log"
assert all(float(r["h"]) <= 2.0 for r in rows), "a step above h_max"
assert sum(float(r["h"]) < 0.1 - 1e-12 for r in rows) <= 2, "steps below h_min"
PY

render --method decoupled --h-max none --accepted-value paper -o d.exr --stats d.json
[ "$(json d.json "d['options']['h_max_voxels']")" = none ]
[ "$(json d.json "d['options']['accepted_value']")" = paper ]

# Skipping empty space changes no bit; uniform Simpson takes no adaptive decision.
render --method coupled --tolerance 0.001 --no-skip-empty -o c2.exr
"$VRI_BIN/vri-diff" c.exr c2.exr --fail 0 > /dev/null
render --method simpson --step 0.25 -o s.exr --stats s.json
[ "$(json s.json "d['stats']['adaptive']['inner_failures'] + d['stats']['adaptive']['outer_failures']")" = 0 ]

expect_error() {  # expect_error PATTERN ARGS...
  local pattern=$1; shift
  set +e; "$VRI_BIN/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 40x30 "$@" -o bad.exr -q 2> err.txt
  local rc=$?; set -e
  [ "$rc" -ne 0 ] || { echo "expected failure for: $*"; exit 1; }
  [ "$(wc -l < err.txt)" -eq 1 ] || { echo "expected one line for: $*"; cat err.txt; exit 1; }
  grep -q -- "$pattern" err.txt || { echo "expected '$pattern' for: $*"; cat err.txt; exit 1; }
  if ls bad.* > /dev/null 2>&1; then echo "output written despite failure: $*"; exit 1; fi
}
expect_error "h_min" --method coupled --h-min 0
expect_error "h_max" --method coupled --h-max 0.2
expect_error "--h-max" --method coupled --h-max lots
expect_error "tolerance" --method coupled --tolerance -1
expect_error "--accepted-value" --method coupled --accepted-value boole
expect_error "--log-ray" --method coupled --log-ray 1,2,3 --log x.csv
expect_error "outside" --method coupled --log-ray 40,0 --log x.csv
expect_error "--log" --method coupled --log x.csv
expect_error "unknown method" --method trapezoid
echo ok
