#!/usr/bin/env bash
# vri-reference end to end: the exact method on paper A's analytic field and on a small raw volume
# (tiny error bound, thread-count independence, Riemann close to it), every kind of bad input giving
# one line, a non-zero exit and no output, then the Bonsai when the data are there.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
command -v python3 >/dev/null || { echo "python3 not installed: skipping"; exit 77; }
bin=$VRI_BIN src=$VRI_SOURCE

# The largest error bound of a stats file, over the four channels.
max_bound() { /usr/bin/python3 -c 'import json, sys; print(max(json.load(open(sys.argv[1]))["stats"]["error_bound"]["max"]))' "$1"; }
below() { /usr/bin/python3 -c 'import sys; sys.exit(0 if float(sys.argv[1]) < float(sys.argv[2]) else 1)' "$1" "$2"; }

# Paper A's linear field: exact to the bound, and Riemann at a small step within its O(h) error.
field=(--field linear --convention node --tf "$src/experiments/tf/paper-a-linear.yaml" --size 24x18
       --eye -4,1.5,2.5 --target 0,0,0 -q)
"$bin/vri-reference" "${field[@]}" -o lin.exr --png lin.png --error-image lin-bound.exr --stats lin.json
test -s lin.exr && test -s lin.png && test -s lin-bound.exr || fail "outputs missing"
grep -q '"sha512"' lin.json && grep -q '"tool": "vri-reference"' lin.json && grep -q '"median_wall_seconds"' lin.json \
    || fail "stats lack provenance: $(cat lin.json)"
below "$(max_bound lin.json)" 1e-9 || fail "error bound $(max_bound lin.json) on the linear field"
"$bin/vri-reference" "${field[@]}" --method riemann --step 0.01 -o lin-riemann.exr --stats lin-riemann.json
grep -q '"step_voxels": 0.01' lin-riemann.json || fail "riemann stats lack the step: $(cat lin-riemann.json)"
"$bin/vri-diff" lin.exr lin-riemann.exr --fail 0.01 --warn 0.01 > /dev/null || fail "riemann 0.01 far from exact on the linear field"

# A deterministic 8x8x8 uint8 volume, cell-centred, non-unit spacing: the same on 1 and 2 threads.
source "$(dirname "${BASH_SOURCE[0]}")/lib/blob.sh" && write_blob_volume
cat > tf.yaml <<'YAML'
points:
  - [0.0, 0.0, 0.0, 0.0, 0.0]
  - [0.3, 0.0, 0.0, 0.0, 0.0]
  - [0.7, 1.0, 0.5, 0.2, 0.4]
  - [0.7, 0.2, 0.5, 1.0, 0.9]
  - [1.0, 1.0, 1.0, 1.0, 0.8]
YAML
blob=(--volume blob_8x8x8_uint8.raw --spacing 1,0.75,1 --tf tf.yaml --size 40x30 -q)
"$bin/vri-reference" "${blob[@]}" --threads 1 -o t1.exr --stats t1.json
"$bin/vri-reference" "${blob[@]}" --threads 2 --repeat 2 -o t2.exr
"$bin/vri-diff" t1.exr t2.exr --fail 0 > /dev/null || fail "the image depends on the thread count"
below "$(max_bound t1.json)" 1e-9 || fail "error bound $(max_bound t1.json) on the blob"
"$bin/vri-reference" "${blob[@]}" --method riemann --step 0.01 -o blob-riemann.exr
"$bin/vri-diff" t1.exr blob-riemann.exr --fail 0.01 --warn 0.01 > /dev/null || fail "riemann 0.01 far from exact on the blob"

# Bad input: one line on stderr that names the problem, a non-zero exit, nothing written.
expect_error() {  # expect_error PATTERN ARGS...
    local pattern=$1; shift
    set +e; "$bin/vri-reference" "$@" -o bad.exr --png bad.png --stats bad.json -q 2> err.txt; local rc=$?; set -e
    [ "$rc" -ne 0 ] || fail "expected failure for: $*"
    [ "$(wc -l < err.txt)" -eq 1 ] || fail "expected one line for: $* (got: $(cat err.txt))"
    grep -q -- "$pattern" err.txt || fail "expected '$pattern' for: $* (got: $(cat err.txt))"
    if ls bad.* > /dev/null 2>&1; then fail "output written despite failure: $*"; fi
}
head -c 500 blob_8x8x8_uint8.raw > short_8x8x8_uint8.raw
expect_error "--method" "${blob[@]}" --method simpson
expect_error "--step applies to --method riemann" "${blob[@]}" --step 0.1
expect_error "--step" "${blob[@]}" --method riemann --step 0
expect_error "--tolerance" "${blob[@]}" --tolerance -1
expect_error "--error-image needs --method exact" "${blob[@]}" --method riemann --error-image bad-bound.exr
expect_error "short_8x8x8_uint8.raw" --volume short_8x8x8_uint8.raw --tf tf.yaml
expect_error "missing.yaml" --volume blob_8x8x8_uint8.raw --tf missing.yaml
expect_error "--size" "${blob[@]}" --size 0x30
expect_error "--field" --field cubic --tf tf.yaml
# Through a file: grep -q stops reading at the match, and a help text longer than a pipe write then dies of SIGPIPE.
"$bin/vri-reference" --help > help.txt && grep -q "Example" help.txt || fail "no examples in --help"

# The Bonsai of paper B, small: exact with a tiny bound, paper B's reference within 0.01 of it.
bonsai="${VRI_DATA_DIR:-$src/../shared/data/volumes}/bonsai_256x256x256_uint8.raw"
if [[ ! -f $bonsai ]]; then
    echo "no $bonsai: skipping the Bonsai check"
    exit 77
fi
scene=(--volume "$bonsai" --tf "$src/experiments/tf/bonsai.yaml" --size 80x60 -q)
"$bin/vri-reference" "${scene[@]}" -o bonsai.exr --stats bonsai.json
below "$(max_bound bonsai.json)" 1e-9 || fail "error bound $(max_bound bonsai.json) on the Bonsai"
"$bin/vri-reference" "${scene[@]}" --method riemann --step 0.01 -o bonsai-riemann.exr
"$bin/vri-diff" bonsai.exr bonsai-riemann.exr --fail 0.01 --warn 0.01 > /dev/null || fail "riemann 0.01 far from exact on the Bonsai"
echo "reference: all checks passed"
