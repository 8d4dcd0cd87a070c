#!/usr/bin/env bash
# Observed orders of convergence end to end: vri-tabulate's convergence layout fits the slope of
# log(error) against log(h) (checked on made-up diffs with known slopes), and an experiment's sweep on the
# analytic ramp gives Riemann order 1 and composite order 2 under Entry Exit Align Corner, within 0.2, with
# the fitted max order in the points CSV's legend and in the figure's key.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"

# Made-up diffs: largest error h^2 in one channel (R), mean error h^3 (both channels' mean_abs h^3), with an
# order-1 start at h = 0.8 that the asymptotic range (the three smallest steps above float rounding) leaves out;
# one error at float rounding.
diff_json() {  # FILE MAX_R MEAN
    printf '{"channels": [{"name": "R", "max_abs": %s, "mean_abs": %s}, {"name": "A", "max_abs": 1e-9, "mean_abs": %s}]}\n' \
        "$2" "$3" "$3" > "$1"
}
diff_json d0.json 5 0.9; diff_json d1.json 0.16 0.064; diff_json d2.json 0.04 0.008; diff_json d3.json 0.01 0.001
diff_json d4.json 1e-8 1e-9
"$VRI_BIN/vri-tabulate" --layout convergence --point square 0.8 d0.json --point square 0.4 d1.json \
    --point square 0.2 d2.json --point square 0.1 d3.json --point square 0.05 d4.json --point flat - d4.json \
    -o t.md --csv t.csv --points p.csv
[[ $(head -1 t.csv) == "series,local max orders,points,h max,h min,max error at h max,max error at h min,max order,max fitted from h,mean error at h max,mean error at h min,mean order,mean fitted from h,error bound,min local order,max local order" ]] ||
    fail "header: $(head -1 t.csv)"
# The local orders between neighbouring steps above float rounding: log(5 / 0.16) / log 2, then 2 and 2.
grep -q '^square,4.97 2.00 2.00,5,0.8,0.05,5,1e-08,2.00,0.4,0.9,1e-09,3.00,0.4,,2.00,4.97$' t.csv || fail "the square series: $(cat t.csv)"
grep -q '^flat,-,,,,,1e-08,,,,1e-09,,,,,$' t.csv || fail "a run without a step: $(cat t.csv)"
[[ $(wc -l < p.csv) == 5 ]] || fail "the points at float rounding are plotted: $(cat p.csv)"
grep -q '^square,0.10000000000000001,0.01,square: max order 2.00$' p.csv || fail "points: $(cat p.csv)"

cat > tf.yaml <<'YAML'
points:
  - [0.0, 0.2, 0.5, 0.9, 0.3]
  - [1.0, 1.0, 0.3, 0.1, 1.2]
YAML
cat > plot.yaml <<'YAML'
x: {label: h, log: true}
y: {label: max error, log: true}
series:
  - {file: orders-points.csv, x: h, y: error, style: linespoints, where: {series: riemann}, label_from: legend}
  - {file: orders-points.csv, x: h, y: error, style: linespoints, where: {series: composite}, label_from: legend}
YAML
cat > exp.yaml <<'YAML'
name: orders
title: Observed orders on the ramp
paper: {paper: none, item: none, says: a test}
scenes:
  ramp: {field: linear, field_dims: [5, 5, 5], convention: node, tf: tf.yaml, size: [6, 6],
         camera: {eye: [-6.3, 3.9, 2.1], target: [0, 0, 0], up: [0, 1, 0]}}
references:
  exact: {method: exact}
methods:
  riemann: {placement: entry-exit-corner, step: [0.2, 0.1, 0.05, 0.025]}
  composite: {placement: entry-exit-corner, step: [0.2, 0.1, 0.05, 0.025]}
comparisons:
  vs-exact: {reference: exact}
tables:
  orders: {layout: convergence, title: Observed orders, comparisons: [vs-exact]}
YAML
drawing=$(command -v gnuplot || true)
[[ -z $drawing ]] || printf 'figures:\n  orders: {spec: plot.yaml, data: [orders-points.csv]}\n' >> exp.yaml
"$VRI_BIN/vri-run" --dry-run --results out exp.yaml > commands.sh
grep -q -- "--point riemann 0.2 out/orders/vs-exact-riemann-h0.2.json out/orders/riemann-h0.2.json " commands.sh ||
    fail "the table's command: $(grep vri-tabulate commands.sh)"
"$VRI_BIN/vri-run" --results out exp.yaml 2> run.txt || fail "the run failed: $(cat run.txt)"
slope() { awk -F, -v s="$1" '$1 == s { print $8 }' out/orders/orders.csv; }  # the max order
awk -v p="$(slope riemann)" 'BEGIN { exit !(p > 0.8 && p < 1.2) }' || fail "Riemann's order: $(cat out/orders/orders.csv)"
awk -v p="$(slope composite)" 'BEGIN { exit !(p > 1.8 && p < 2.2) }' || fail "composite's order: $(cat out/orders/orders.csv)"
grep -q "^riemann,.*,riemann: max order $(slope riemann)\$" out/orders/orders-points.csv || fail "legend: $(cat out/orders/orders-points.csv)"
if [[ -z $drawing ]]; then
    echo "gnuplot not installed: skipping the figure"
    exit 77
fi
grep -q "title 'composite: max order $(slope composite)'" out/orders/orders.gp || fail "the key: $(grep title out/orders/orders.gp)"
echo "convergence: all checks passed"
