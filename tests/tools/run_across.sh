#!/usr/bin/env bash
# Step caching across experiments (issue 29 item 7): experiment A's figure reads a CSV that experiment B's
# command writes (its spec names ../across-b/tf.csv; A lists no `data`). When B's output changes, A's figure
# is drawn again: in one vri-run whatever the order of the files (B runs first), and in two runs (the
# figure step is keyed by that file's content). Nothing changed, nothing runs. Two experiments that read
# each other's results are refused with one line.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
cd "$VRI_SCRATCH"
run="$VRI_BIN/vri-run"
scene='scenes: {red: {field: linear, field_dims: [5, 5, 5], convention: node, tf: SCENE_TF, size: [8, 6]}}'
experiment() {  # NAME SCENE_TF: the head of an experiment file with one render
  printf 'name: %s\ntitle: %s\npaper: {paper: none, item: test, says: a test}\n%s\nmethods: {riemann: {rate: 1}}\n' \
    "$1" "$1" "${scene/SCENE_TF/$2}"
}
tf() { printf 'points: [[0, 0, 0, 0, 0], [1, 1, 1, 1, %s]]\n' "$1" > tf.yaml; }
tf 1
cp tf.yaml tf-a.yaml
{ experiment across-b tf-a.yaml; echo 'commands: {tf: {tool: vri-tf, inputs: {tf: tf.yaml}, outputs: {o: tf.csv}}}'; } > b.yaml
{ experiment across-a tf-a.yaml; echo 'figures: {curve: {spec: curve.yaml}}'; } > a.yaml
echo 'series: [{file: ../across-b/tf.csv, x: s, y: tau, style: line}]' > curve.yaml

figure() { sha256sum < out/across-a/curve.png; }
ran() {  # EXPERIMENT: "<ran> ran, <cached> cached" of its last summary line
  grep -o "$1: [0-9]* steps, [0-9]* ran, [0-9]* cached" log | tail -n 1 | sed 's/.*steps, //'
}

"$run" --results out a.yaml b.yaml 2> log || fail "A before B on the command line, first run: $(cat log)"
[ "$(grep -o 'across-[ab]: [0-9]* steps' log | cut -d: -f1 | tr '\n' ' ')" = "across-b across-a " ] ||
  fail "B, whose output A reads, did not run first: $(cat log)"
first=$(figure)

# One run, A named first: B runs first, and A's figure (only) is drawn again from B's new CSV.
tf 4
"$run" --results out a.yaml b.yaml 2> log || fail "second run: $(cat log)"
[ "$(ran across-b)" = "1 ran, 1 cached" ] || fail "B: $(ran across-b), expected its command to run again"
[ "$(ran across-a)" = "1 ran, 1 cached" ] || fail "A, one run: $(ran across-a), expected its figure to run again"
second=$(figure)
[ "$first" != "$second" ] || fail "A's figure was not drawn again from B's new output"

# Two runs: B alone, then A alone; A's figure step sees the CSV's new content.
tf 2
"$run" --results out b.yaml 2> log || fail "B alone: $(cat log)"
"$run" --results out a.yaml 2>> log || fail "A alone: $(cat log)"
[ "$(ran across-a)" = "1 ran, 1 cached" ] || fail "A, second run: $(ran across-a), expected its figure to run again"
[ "$(figure)" != "$second" ] || fail "A's figure was not drawn again in a run of its own"
grep -q '"path": "out/across-b/tf.csv"' out/across-a/manifest.json || fail "A's manifest does not list B's CSV as read"

# Nothing changed: nothing runs.
"$run" --results out a.yaml b.yaml 2> log || fail "run with nothing changed: $(cat log)"
[ "$(ran across-a)" = "0 ran, 2 cached" ] && [ "$(ran across-b)" = "0 ran, 2 cached" ] || fail "not all cached: $(cat log)"
# --dry-run prints the commands in the order they run.
"$run" --dry-run --results out a.yaml b.yaml > dry.txt
[ "$(grep -n 'vri-tf' dry.txt | cut -d: -f1)" -lt "$(grep -n 'vri-plot' dry.txt | cut -d: -f1)" ] ||
  fail "--dry-run: vri-plot before the vri-tf whose CSV it reads: $(cat dry.txt)"

# A reads B's results and B reads A's: no order works.
{ experiment across-b tf-a.yaml
  echo 'commands: {tf: {tool: vri-tf, inputs: {tf: tf.yaml}, outputs: {o: tf.csv}}}'
  echo 'figures: {back: {spec: back.yaml}}'; } > b2.yaml
echo 'series: [{file: ../across-a/curve-data.csv, x: s, y: tau}]' > back.yaml
{ experiment across-a tf-a.yaml
  echo 'commands: {data: {tool: vri-tf, inputs: {tf: tf.yaml}, outputs: {o: curve-data.csv}}}'
  echo 'figures: {curve: {spec: curve.yaml}}'; } > a2.yaml
rc=0
"$run" --dry-run --results out a2.yaml b2.yaml > /dev/null 2> err || rc=$?
[ "$rc" -eq 1 ] && [ "$(wc -l < err)" -eq 1 ] &&
  grep -Eq '^vri-run: error: a2\.yaml reads .*/out/across-b/tf\.csv, which b2\.yaml writes, and b2\.yaml reads \(in turn\) what a2\.yaml writes' err ||
  fail "a cycle between experiments: exit $rc, $(cat err)"
echo "run_across: ok"
