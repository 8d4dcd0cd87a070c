#!/usr/bin/env bash
# vri-verify and vri-outside end to end, with the card's example renderer as the outside renderer: a correct
# renderer passes every finding (order of convergence, placement, orientation), and each injected defect
# (an image upside down, the wrong placement, no opacity correction; jitter that ignores the seed or is not
# uniform over the step) fails with exit 3 and a message that names it. Then docs/ci-recipe.md's verification step runs as written.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
bin=${VRI_BIN:?} src=${VRI_SOURCE:?}
python=/usr/bin/python3
"$python" -c 'import numpy, OpenImageIO' 2> /dev/null || { echo "needs python3-numpy and python3-openimageio: skipping"; exit 77; }
source "$(dirname "${BASH_SOURCE[0]}")/lib/blob.sh" && write_blob_scene
buggy=(-- "$python" "$src/tests/tools/lib/buggy_renderer.py")
scene=(--volume blob_8x8x8_uint8.raw --tf tf.yaml --size 24x18 --renderer-image f32 -q)

# vri-outside: one run's image is the renderer's, and its record says what ran.
"$bin/vri-outside" "${scene[@]}" --step 0.5 -o one.exr --png one.png --stats one.json "${buggy[@]}" none {card} {output}
"$bin/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 24x18 -q --step 0.5 --precision double -o vri.exr
"$bin/vri-diff" vri.exr one.exr --fail 1e-6 > /dev/null
"$python" - one.json <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
assert r["tool"] == "vri-outside" and r["stats"]["backend"] == "outside", r["stats"]
assert r["renderer"]["executable"]["sha512"] and r["renderer"]["quantisation"] == "float32"
assert r["timing"]["timed"] == "process" and r["timing"]["median_wall_seconds"] > 0
assert r["options"]["step_voxels"] == 0.5
PY
[ -z "$(ls -A | grep '^\.vri-outside-')" ] || fail "vri-outside left its work folder"

verify() {  # verify EXPECTED_EXIT PATTERN BUG [OPTIONS...]
  local want=$1 pattern=$2 bug=$3; shift 3
  set +e
  "$bin/vri-verify" "${scene[@]}" --steps "${steps:-2,1,0.5,0.25}" "$@" --report "$bug.md" --json "$bug.json" \
    --junit "$bug.xml" "${buggy[@]}" "$bug" {card} {output} 2> "$bug.err"
  local rc=$?
  set -e
  [ "$rc" -eq "$want" ] || { cat "$bug.err"; fail "$bug: exit $rc, expected $want"; }
  grep -Eq -- "$pattern" "$bug.err" || { cat "$bug.err"; fail "$bug: expected '$pattern'"; }
  grep -q '<testsuite' "$bug.xml" && grep -q "^\*\*Verification of " "$bug.md"
}
verify 0 "pass: convergence: observed order (0\.9|1\.0)" none --placement eye
verify 3 "FAIL: orientation: the image is upside down" flip
verify 3 "FAIL: placement: uses placement entry .* but the card asks for eye" entry-placement --placement eye
verify 3 "FAIL: convergence: .*the error does not fall with the step. Does the renderer take the card's step, and correct the opacity" no-opacity-correction
"$python" - none.json <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
assert r["passed"] and r["placement"] == "eye" and not r["upside_down"], r
assert 0.85 < r["order"] < 1.2, r["order"]   # a Riemann sum: first order
PY
# Its record says where an input's digest came from when vri-run's record gave it (util/input_digest.h).
"$python" - <<'PY'
import json, os
st = os.stat("blob_8x8x8_uint8.raw")
json.dump({"files": [{"path": os.path.abspath("blob_8x8x8_uint8.raw"), "size": st.st_size,
                      "mtime_ns": st.st_mtime_ns, "sha512": "from-the-record"}]}, open("record.json", "w"))
PY
VRI_INPUT_DIGESTS=$PWD/record.json verify 0 "pass: convergence" none --placement eye
"$python" - none.json "$PWD/record.json" <<'PY' || fail "vri-verify's record of its inputs' digests"
import json, sys
r = json.load(open(sys.argv[1]))
assert r["inputs"][0]["sha512"] == "from-the-record" and r["input_digests_from"] == sys.argv[2], (r["inputs"], r.get("input_digests_from"))
PY

# Jittered renderers, each card run with 12 seeds: the example renderer (vri's own hash: the same frames) and
# one with random numbers of its own pass; one that ignores the seed, and one whose first sample falls in the
# first half of the step only, fail. The permutation test is exact, and the seeds fixed: the verdicts are too.
steps=2,1,0.5
verify 0 "pass: jitter: its frames are distributed as the card's jittered Riemann sum's" none --jitter --seeds 12
verify 0 "pass: jitter: .*smallest p (0\.[1-9]|1 )" jitter-other-seeds --jitter --seeds 12 --seed 40
# --renderer-jobs 2: the same 12 runs two at a time (each seed's run waits for its partner's, 40 and 41, ...,
# and fails alone), the same report but for times.
cp jitter-other-seeds.json other-seeds-one-at-a-time.json
mkdir pairs
VRI_TEST_PAIRED_RUNS=$PWD/pairs verify 0 "pass: jitter: .*smallest p (0\.[1-9]|1 )" jitter-other-seeds --jitter --seeds 12 \
  --seed 40 --renderer-jobs 2
[ "$(ls pairs | wc -l)" -eq 36 ] || fail "$(ls pairs | wc -l) paired runs, not 12 seeds at 3 steps"
"$python" - other-seeds-one-at-a-time.json jitter-other-seeds.json <<'PY'
import json, sys
def timeless(x):
    if isinstance(x, dict):
        return {k: timeless(v) for k, v in x.items() if "second" not in k and k not in ("command", "argv")}
    return [timeless(v) for v in x] if isinstance(x, list) else x
one, five = (timeless(json.load(open(f))) for f in sys.argv[1:])
assert one == five, "--renderer-jobs 2 changed the report"
PY
verify 3 "FAIL: jitter: the 12 frames of every card are identical: the renderer does not jitter, or does not take the card's seed" \
  jitter-ignores-seed --jitter --seeds 12
verify 3 "FAIL: jitter: its frames are not distributed as the card's jittered Riemann sum's .*smallest p 0\.001" \
  jitter-half --jitter --seeds 12
"$python" - jitter-half.json <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
assert r["placement"] == "jittered" and r["jitter"]["differs"] and r["jitter"]["seeds"] == 12, r["jitter"]
for row in r["steps"]:   # the defect is bias, not noise: more of it than vri's own jittered sum has
    assert row["renderer"]["bias_rms"] > row["vri"]["bias_rms"], row
PY
"$python" - none.json <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
assert r["jitter"]["smallest_p"] == 1 and r["jitter"]["differing"] == 0, r["jitter"]   # vri's own frames, bit for bit
PY
unset steps
bad() {  # bad PATTERN OPTIONS...: a usage error (exit 64) naming the option
  local pattern=$1; shift
  set +e
  "$bin/vri-verify" "${scene[@]}" "$@" -- "$python" -c pass 2> usage.err
  local rc=$?
  set -e
  [ "$rc" -eq 64 ] && grep -q -- "$pattern" usage.err || { cat usage.err; fail "expected exit 64 and '$pattern' (exit $rc)"; }
}
bad "^vri-verify: error: --seeds: tests a jittered renderer; give --jitter" --seeds 8
bad "^vri-verify: error: --jitter: a jittered renderer is verified over seeds" --jitter
bad "^vri-verify: error: --frames: vri-verify runs each card once per seed" --jitter --seeds 4 --frames 2
bad "^vri-verify: error: --seeds" --jitter --seeds 0

# docs/ci-recipe.md's verification step, as written, with ./my-renderer the example renderer.
printf '#!/bin/sh\nexec %s %s "$@"\n' "$python" "$src/examples/scene_card/render_from_card.py" > my-renderer
chmod +x my-renderer
sed -n '/^ *# vri-verify: begin/,/^ *# vri-verify: end/p' "$src/docs/ci-recipe.md" | sed 's/^ \{14\}//' > recipe.sh
[ "$(wc -l < recipe.sh)" -gt 3 ] || fail "docs/ci-recipe.md: no verification step between its markers"
PATH="$bin:$PATH" bash -e recipe.sh
grep -q 'failures="0"' vri-junit.xml || fail "the recipe's JUnit report has failures"
echo "vri-verify: a correct renderer passes, three injected defects are named, and so are two jitter defects"
