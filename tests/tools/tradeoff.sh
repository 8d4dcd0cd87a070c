#!/usr/bin/env bash
# Speed against accuracy end to end: an experiment's tradeoff table (vri-run -> vri-tabulate) from the
# renders' stats and the comparisons' diffs, Pareto flags that agree with the numbers, a second run all
# cached, and its figure (vri-plot): every run labelled, the front drawn through the points drawn.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"

cat > tf.yaml <<'YAML'
points:
  - [0.0, 0.0, 0.0, 0.0, 0.0]
  - [1.0, 1.0, 0.6, 0.2, 0.8]
YAML
mkdir plots
cat > plots/speed.yaml <<'YAML'
title: time against error
size: [1000, 450]
panels:
  - title: "% of rays above 0.001"
    x: {label: seconds per frame, log: true}
    y: {label: "% of rays, worst channel"}
    pareto: true
    series:
      - {file: speed.csv, x: seconds, y: "worst > 0.001", style: points, labels: run, label: runs}
  - title: max |error|
    x: {label: seconds per frame, log: true}
    y: {label: max |error|, log: true}
    pareto: true
    series:
      - {file: speed.csv, x: seconds, y: max, style: points, labels: run, label: runs}
      - {file: speed.csv, x: seconds, y: max, style: points, point: square, size: 1.5, where: {pareto max: 1}, label: on the front}
YAML
cat > exp.yaml <<'YAML'
name: small
title: Riemann steps against composite steps
paper: {paper: B, item: Table III, says: a test}
scenes:
  s: {field: linear, field_dims: [5, 5, 5], convention: node, tf: tf.yaml, size: [24, 16],
      camera: {eye: [-8, 4, 1], target: [0, 0, 0], up: [0, 0, 1]}}
references:
  exact: {method: riemann, step: 0.01}
methods:
  riemann: {step: [1, 0.5, 0.25]}
  composite: {step: [1, 0.25], repeat: 2}
comparisons:
  vs-riemann: {reference: exact, runs: [riemann-h1, riemann-h0.5, riemann-h0.25]}
  vs-composite: {reference: exact, runs: [composite-h1, composite-h0.25]}
tables:
  speed:
    layout: tradeoff
    title: Seconds per frame against error
    comparisons: [vs-riemann, vs-composite]
    threshold: 0.001
  bench:
    layout: tradeoff
    title: Each time over Riemann h = 1's
    comparisons: [vs-riemann, vs-composite]
    threshold: [0.001, 0.01]
    baseline: riemann-h1
    channels: worst
YAML
# The figure needs gnuplot; without it the table is checked alone.
drawing=$(command -v gnuplot || true)
[[ -z $drawing ]] || printf 'figures:\n  speed: {spec: plots/speed.yaml, data: [speed.csv]}\n' >> exp.yaml

"$VRI_BIN/vri-run" --dry-run --results out exp.yaml > commands.sh
grep -q -- "vri-tabulate --layout tradeoff --title 'Seconds per frame against error' --threshold 0.001 --run riemann-h1 out/small/riemann-h1.json out/small/vs-riemann-riemann-h1.json --run riemann-h0.5 " commands.sh ||
    fail "the table's command: $(grep vri-tabulate commands.sh)"
"$VRI_BIN/vri-run" --results out exp.yaml 2> first.txt || fail "the run failed: $(cat first.txt)"
table=out/small/speed.csv
[[ $(head -1 $table) == "run,method,seconds,frames,spread %,ci low,ci high,Msamples/s,R > 0.001,G > 0.001,B > 0.001,A > 0.001,worst > 0.001,max R,max G,max B,max A,max,rmse,PSNR dB,SSIM,FLIP,pareto %,pareto max" ]] ||
    fail "header: $(head -1 $table)"
[[ $(cut -d, -f1 $table | tail -n +2 | tr '\n' ' ') == "riemann-h1 riemann-h0.5 riemann-h0.25 composite-h1 composite-h0.25 " ]] ||
    fail "rows: $(cut -d, -f1 $table)"
grep -q "^| riemann-h0.25 | riemann double | " out/small/speed.md || fail "Markdown: $(cat out/small/speed.md)"
grep -q "^composite-h1,composite double," $table || fail "method of composite-h1: $(grep composite-h1 $table)"

# Each flag as the numbers say: 1 exactly when no other row is at least as fast and as accurate and
# better in one (seconds: column 3; worst %: column 13; max: column 18; flags: columns 23 and 24).
awk -F, 'NR > 1 { n++; t[n] = $3; p[n] = $13; m[n] = $18; fp[n] = $23; fm[n] = $24 }
         function dominated(i, e,   j) {
             for (j = 1; j <= n; j++)
                 if (j != i && t[j] <= t[i] && e[j] <= e[i] && (t[j] < t[i] || e[j] < e[i])) return 1
             return 0 }
         END { for (i = 1; i <= n; i++)
                   if (fp[i] != 1 - dominated(i, p) || fm[i] != 1 - dominated(i, m)) { print "row " i; bad = 1 }
               exit bad }' $table || fail "Pareto flags disagree with the numbers: $(cat $table)"

# The benchmark form: each run's time over the baseline's, measured in the same run; the worst channel at
# both thresholds; samples per second from the stats.
bench=out/small/bench.csv
[[ $(head -1 $bench) == "run,method,seconds,frames,spread %,ci low,ci high,time ratio,Msamples/s,worst > 0.001,worst > 0.01,max,rmse,PSNR dB,SSIM,FLIP,pareto %,pareto max" ]] ||
    fail "bench header: $(head -1 $bench)"
# Seconds and ratios are printed to 4 significant digits, each off by at most 5e-4 of itself, so a ratio
# recomputed from two printed times may differ from the printed one by up to about 1.5e-3 of it.
base=$(awk -F, '$1 == "riemann-h1" { print $3 }' $bench)
awk -F, -v base="$base" 'NR > 1 { r = $3 / base; if ((r - $8) / r > 1.6e-3 || ($8 - r) / r > 1.6e-3) { print $1; bad = 1 } }
                          END { exit bad }' $bench || fail "time ratios disagree with the seconds: $(cat $bench)"
grep -q "^riemann-h1,riemann double,[0-9.e+-]*,[0-9]*,[0-9.e+-]*,[0-9.e+-]*,[0-9.e+-]*,1," $bench || fail "the baseline's ratio is not 1: $(cat $bench)"
number() { grep -o "\"$1\": [0-9.e+-]*" out/small/riemann-h0.5.json | head -1 | cut -d' ' -f2; }
evaluated=$(number samples_evaluated) median=$(number median_wall_seconds)
awk -F, -v n="$evaluated" -v t="$median" '$1 == "riemann-h0.5" { s = n / t / 1e6; d = ($9 - s) / s; exit !(d < 5e-4 && d > -5e-4) }' $bench ||
    fail "Msamples/s of riemann-h0.5: $(grep riemann-h0.5 $bench), stats say $evaluated samples in $median s"

"$VRI_BIN/vri-run" --results out exp.yaml 2> second.txt
grep -q "0 ran" second.txt || fail "a second run ran steps: $(cat second.txt)"

if [[ -z $drawing ]]; then
    echo "gnuplot not installed: skipping the figure"
    exit 77
fi
# The figure: a label per run and the front of the points drawn.
script=out/small/speed.gp
grep -q "with labels left offset char 0.5,0.5 font ',8' notitle" $script || fail "no labels: $(cat $script)"
grep -q '^\$pareto2 << EOD' $script || fail "no front: $(cat $script)"
grep -q "riemann-h0.25" out/small/speed.svg || fail "the SVG has no run labels"
echo "tradeoff: all checks passed"
