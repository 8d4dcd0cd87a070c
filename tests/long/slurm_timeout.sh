#!/usr/bin/env bash
# vri-run --slurm-retries after TIMEOUT on a real cluster (tests/tools/lib/slurm_cluster.sh): an outside
# renderer that takes 105 s, whose job a site profile gives 1 minute, times out; retried with --time doubled,
# it completes, one line saying so and the manifest naming the attempt before. Slurm's smallest limit is a
# minute and it looks for jobs past theirs every 30 s or so (so the first attempt ends 60 to 90 s in, the second
# at 105 s, before its 120), so this takes about 4 minutes, most of it waiting:
# `make test-slurm-timeout`, not part of `make test`. Needs root (slurmd).
#   VRI_BIN=$PWD/build/bin VRI_SOURCE=$PWD VRI_SCRATCH=$PWD/build/slurm-timeout tests/long/slurm_timeout.sh
source "${VRI_SOURCE:?}/tests/tools/lib/scratch.sh"
source "$VRI_SOURCE/tests/tools/lib/slurm_cluster.sh"
bin=${VRI_BIN:?} src=$VRI_SOURCE
start_slurm_cluster "$PWD/cluster"
source "$src/tests/tools/lib/blob.sh" && write_blob_scene
cp "$src/examples/scene_card/render_from_card.py" .  # named in the YAML below by a plain relative name
cat > late.yaml <<YAML
name: late
title: An outside renderer slower than its job's time limit
paper: {paper: A, item: none, says: a test}
scenes:
  blob: {volume: blob_8x8x8_uint8.raw, convention: cell, tf: tf.yaml, size: [24, 18]}
renderers:
  sleepy:   # the card's example renderer after 105 s; the card's and image's paths reach it as arguments
    command: [/bin/sh, -c, 'sleep 105 && exec /usr/bin/python3 "\$0" "\$1" "\$2"', render_from_card.py, "{card}", "{output}"]
    image: f32
methods:
  late: {renderer: sleepy, step: 0.5}
YAML
printf 'kinds:\n  outside: {time: 1}\n' > one-minute.yaml
VRI_SLURM_PROFILE=$PWD/one-minute.yaml "$bin/vri-run" --executor slurm --slurm-poll 1 --slurm-retries 1 --results res \
    late.yaml 2> run.txt || { cat run.txt; fail "the run retried after TIMEOUT failed"; }
grep -q "^vri-run: late: step 'late': Slurm job [0-9]* TIMEOUT on vri-test-node; retrying (attempt 2 of 2, --time x2)$" run.txt ||
    { cat run.txt; fail "no line saying the job that timed out is retried with --time doubled"; }
/usr/bin/python3 - <<'PY' || fail "the manifest does not name the attempt that timed out"
import json, re
step = json.load(open("res/late/manifest.json"))["steps"][0]
attempts = step["execution"].get("earlier_attempts", [])
assert len(attempts) == 1 and re.fullmatch(r"job \d+ TIMEOUT on vri-test-node", attempts[0]), attempts
PY
[ -s res/late/late.exr ] || fail "no image"
echo "slurm_timeout: OK"
