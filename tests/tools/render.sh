#!/usr/bin/env bash
# vri-render end to end: a tiny volume rendered, compared with itself and with a changed render,
# thread-count independence, and every kind of bad input giving one line, a non-zero exit and no output.
set -euo pipefail
bin=${VRI_BIN:?} src=${VRI_SOURCE:?} dir=${VRI_SCRATCH:?}
rm -rf "$dir" && mkdir -p "$dir" && cd "$dir"

# A deterministic 8x8x8 uint8 volume: a ramp with some structure.
source "$(dirname "${BASH_SOURCE[0]}")/lib/blob.sh" && write_blob_scene
render() { "$bin/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 40x30 -q "$@"; }

render --step 0.5 -o a.exr --png a.png --stats a.json
test -s a.exr && test -s a.png && grep -q '"samples_evaluated"' a.json && grep -q '"sha512"' a.json
"$bin/vri-diff" a.exr a.exr --fail 0 > /dev/null   # identical: exit 0

render --step 0.25 -o b.exr
set +e; "$bin/vri-diff" a.exr b.exr > /dev/null; rc=$?; set -e
[ "$rc" -ne 0 ] || { echo "diff of different renders exited 0"; exit 1; }

# Bitwise the same on 1 and 2 threads, and with empty-space skipping off.
render --step 0.5 --threads 1 -o t1.exr
render --step 0.5 --threads 2 --no-skip-empty -o t2.exr
"$bin/vri-diff" a.exr t1.exr --fail 0 > /dev/null
"$bin/vri-diff" a.exr t2.exr --fail 0 > /dev/null

# Bad input: one line on stderr that names the problem, a non-zero exit, nothing written.
expect_error() {  # expect_error PATTERN ARGS...
  local pattern=$1; shift
  set +e; "$bin/vri-render" "$@" -o bad.exr --png bad.png --stats bad.json -q 2> err.txt; local rc=$?; set -e
  if [ "$rc" -eq 0 ]; then echo "expected failure for: $*"; exit 1; fi
  if [ "$(wc -l < err.txt)" -ne 1 ]; then echo "expected one line for: $*"; cat err.txt; exit 1; fi
  grep -q -- "$pattern" err.txt || { echo "expected '$pattern' for: $*"; cat err.txt; exit 1; }
  if ls bad.* > /dev/null 2>&1; then echo "output written despite failure: $*"; exit 1; fi
}
head -c 500 blob_8x8x8_uint8.raw > short_8x8x8_uint8.raw
printf 'points:\n  - [0.5, 0, 0, 0, 0]\n  - [0.2, 0, 0, 0, 0]\n' > unsorted.yaml
printf 'points:\n  - [0.5, 0, 0, 0, -1]\n' > negative.yaml
printf 'points: [[0, 0\n' > malformed.yaml
expect_error "short_8x8x8_uint8.raw" --volume short_8x8x8_uint8.raw --tf tf.yaml
expect_error "int7" --volume blob_8x8x8_uint8.raw --dims 8,8,8 --type int7 --tf tf.yaml
expect_error "missing.raw" --volume missing.raw --dims 8,8,8 --type uint8 --tf tf.yaml
expect_error "unsorted.yaml:3:5" --volume blob_8x8x8_uint8.raw --tf unsorted.yaml
expect_error "negative.yaml:2:5" --volume blob_8x8x8_uint8.raw --tf negative.yaml
expect_error "malformed.yaml:2:1: malformed YAML" --volume blob_8x8x8_uint8.raw --tf malformed.yaml
expect_error "--size" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 0x30
expect_error "--step" --volume blob_8x8x8_uint8.raw --tf tf.yaml --step 0
expect_error "--step" --volume blob_8x8x8_uint8.raw --tf tf.yaml --step -0.5
expect_error "placement" --volume blob_8x8x8_uint8.raw --tf tf.yaml --placement middle

# A camera that misses the volume: exit 0 with its empty image, but a warning on stderr and in the stats;
# a camera that sees it, neither.
for tool in vri-render vri-reference; do
    "$bin/$tool" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 8x6 --eye 40,40,40 --target 80,80,80 -q \
        -o miss.exr --stats miss.json 2> miss.txt
    grep -q "^$tool: warning: no ray enters the volume's box: the camera (eye \[40.0,40.0,40.0\], target .*rays_hit 0)$" \
        miss.txt || { echo "$tool: no warning for a camera that misses: $(cat miss.txt)"; exit 1; }
    grep -q '"warnings": \[' miss.json || { echo "$tool: the stats lack the warning"; exit 1; }
    "$bin/$tool" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 8x6 -q -o hit.exr --stats hit.json 2> hit.txt
    [ ! -s hit.txt ] && ! grep -q '"warnings"' hit.json || { echo "$tool: a warning for a camera that sees it"; exit 1; }
    # A tile of background: its own warning, not the camera's.
    "$bin/$tool" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 64x48 --region 0,0,2,2 -q -o tile.exr 2> tile.txt
    grep -q "^$tool: warning: no ray of --region 0,0,2,2 enters the volume's box: the region is background" tile.txt ||
        { echo "$tool: no region warning for a background tile: $(cat tile.txt)"; exit 1; }
done

# More threads than the machine has: the frames run on its cores, said on stderr; the stats hold the count
# that ran. No warning for a count within them.
for tool in vri-render vri-reference; do
    "$bin/$tool" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 8x6 -q --threads 100000 -o t.exr --stats t.json 2> t.txt
    cores=$(/usr/bin/python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["stats"]["threads"])' t.json)
    [ "$cores" -ge 1 ] && [ "$cores" -lt 100000 ] || { echo "$tool: stats threads $cores"; exit 1; }
    grep -qx "$tool: warning: --threads 100000: more than the [0-9]* cores* this process may use; at most [0-9]* run" \
        t.txt || { echo "$tool: no warning for --threads 100000: $(cat t.txt)"; exit 1; }
    "$bin/$tool" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 8x6 -q --threads 1 -o t.exr 2> t.txt
    [ ! -s t.txt ] || { echo "$tool: a warning for --threads 1: $(cat t.txt)"; exit 1; }
done

# A bare volume name is also looked up in $VRI_DATA_DIR (as vri-run and Python do), by vri-render and
# vri-convert alike; a file of that name at hand comes first; the provenance names the file read.
mkdir -p data elsewhere && cp blob_8x8x8_uint8.raw data/only_8x8x8_uint8.raw
render -o direct.exr
(cd elsewhere && VRI_DATA_DIR=$PWD/../data "$bin/vri-render" --volume only_8x8x8_uint8.raw --tf ../tf.yaml --size 40x30 -q \
   -o ../from-data.exr --stats ../from-data.json) || fail "a bare name in \$VRI_DATA_DIR was not found"
"$bin/vri-diff" direct.exr from-data.exr --fail 0 > /dev/null
grep -q '"path": "[^"]*/data/only_8x8x8_uint8.raw"' from-data.json || fail "the stats do not name the file read from \$VRI_DATA_DIR"
(cd elsewhere && VRI_DATA_DIR=$PWD/../data "$bin/vri-convert" only_8x8x8_uint8.raw only.nhdr > /dev/null) || fail "vri-convert: no lookup in \$VRI_DATA_DIR"
if (cd elsewhere && VRI_DATA_DIR=$PWD/../nowhere "$bin/vri-render" --volume only_8x8x8_uint8.raw --tf ../tf.yaml -q -o x.exr 2> ../err.txt); then
  fail "a volume in no folder was read"
fi
grep -q "only_8x8x8_uint8.raw" err.txt || fail "the missing volume is not named: $(cat err.txt)"

help=$("$bin/vri-render" --help)  # captured whole: grep -q on a pipe would cut the writer off (SIGPIPE)
grep -q "Example" <<<"$help"
echo "render: all checks passed"
