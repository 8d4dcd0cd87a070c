#!/usr/bin/env bash
# Timing hygiene: a render timed while other processes keep the cores busy says so. Two busy loops run beside a
# vri-run whose timed render uses every core; the render's stats record the load (timing.load: other processes'
# cores, measured from /proc over the timed frames), vri-run shows the tool's warning, the timed table carries
# a warning note, and the gallery a caption. Every timed record also gives the median's order-statistic
# interval. The loops are stopped by their pids. Nothing here depends on how long anything takes: the loops
# keep a core busy however fast the machine, and the frames are long enough (> 0.25 s in all) to be measured.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
bin=${VRI_BIN:?} src=${VRI_SOURCE:?}
[ -r /proc/stat ] || { echo "no /proc/stat: skipping"; exit 77; }
cat > exp.yaml <<YAML
name: loaded
title: Timed beside a synthetic load
paper: {paper: none, item: timing, says: a test}
scenes:
  cube: {field: linear, field_dims: [16, 16, 16], convention: node, tf: $src/experiments/tf/paper-a-linear.yaml,
         size: [320, 240], camera: {eye: [3.2, 2.1, 4.5], target: [0, 0, 0], up: [0, 1, 0], fov: 40}}
references:
  fine: {method: riemann, step: 0.1}
methods:
  riemann: {step: [0.01], precision: double, repeat: 3, warm_up: 0}
comparisons:
  vs: {reference: fine}
tables:
  speed: {layout: tradeoff, title: "seconds", comparisons: [vs]}
YAML
spinners=()
stop_spinners() { for pid in "${spinners[@]}"; do kill "$pid" 2>/dev/null || true; done; }
trap stop_spinners EXIT
for _ in 1 2; do (while :; do :; done) & spinners+=($!); done
"$bin/vri-run" --results res --gallery res exp.yaml 2> run.txt || { cat run.txt; fail "the run failed"; }
stop_spinners
grep -q "riemann-h0.01: warning: timed while other processes used [0-9.]* cores beside its [0-9]* threads on [0-9]* cores" run.txt ||
  fail "vri-run did not show the render's warning: $(cat run.txt)"
/usr/bin/python3 - res/loaded/riemann-h0.01.json <<'PY' || fail "the stats' timing record: $(cat res/loaded/riemann-h0.01.json)"
import json, sys
t = json.load(open(sys.argv[1]))["timing"]
load = t["load"]
assert load["overloaded"] and load["other_cores"] > 0.5 and load["cores"] >= 1 and load["threads"] >= 1, load
ci = t["median_ci"]
assert ci["low"] <= t["median_wall_seconds"] <= ci["high"] and ci["coverage"] == 0.75, ci   # 3 frames: min to max
PY
grep -q "^Warning: 1 of these 1 runs were timed while other processes kept the cores busy" res/loaded/speed.md ||
  fail "the table has no warning: $(cat res/loaded/speed.md)"
grep -q "^\*Timed under load: 1 run (riemann-h0.01)" res/README.md res/loaded.md 2>/dev/null ||
  fail "the gallery has no caption: $(grep -il load res/*.md)"
echo "timing under load: recorded, warned on the console, in the table and in the gallery"
