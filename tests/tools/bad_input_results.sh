#!/usr/bin/env bash
# vri-run writes into a work tree's results/ only from a clean tree (or with --allow-dirty), and the
# gallery names the commit each experiment's results were made from.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
source "$(dirname "${BASH_SOURCE[0]}")/lib/bad_input.sh"
bin=$VRI_BIN
command -v git > /dev/null || { echo "git not installed: skipped"; exit 77; }
git_q() { git -c user.name=test -c user.email=test@example.invalid -c commit.gpgsign=false "$@" > /dev/null; }

mkdir experiments
cat > experiments/tf.yaml <<'YAML'
points:
  - [0.0, 0.0, 0.0, 0.0, 0.0]
  - [1.0, 1.0, 0.2, 0.1, 0.8]
YAML
cat > experiments/tiny.yaml <<'YAML'
name: tiny
title: One tiny render
paper: {paper: none, item: none, says: a test}
scenes:
  cube: {field: linear, field_dims: [5, 5, 5], convention: node, tf: tf.yaml, size: [8, 6]}
methods:
  riemann: {rate: 1}
YAML
git_q init -q . && git_q add experiments && git_q commit -q -m experiments
echo "# a change" >> experiments/tf.yaml
git update-index -q --refresh || true  # so that the checks below find the index as it stays

bad 1 '^vri-run: error: results: tracked files of .* differ from commit [0-9a-f]{12}; commit them, or pass --allow-dirty$' -- \
    "$bin/vri-run" experiments/tiny.yaml
bad 1 '^vri-run: error: \./results/?: tracked files of ' -- "$bin/vri-run" --results ./results/ experiments/tiny.yaml

# The convergence layout (vri-tabulate) and a key taken from the data (vri-plot).
printf '{"channels": [{"name": "R", "max_abs": 0.5, "mean_abs": 0.1}]}\n' > diff.json
printf 'series,h,error,legend\na,0.1,0.01,a: slope 1.00\n' > points.csv
printf 'series:\n  - {file: points.csv, x: h, y: error, where: {series: b}, label_from: legend}\n' > nokept.yaml
printf 'series:\n  - {file: points.csv, x: h, y: error, label: x, label_from: legend}\n' > both.yaml
bad 1 "^vri-tabulate: error: --point a: step: expected a number > 0, got '0'\$" -- \
    "$bin/vri-tabulate" --layout convergence --point a 0 diff.json -o t.md
bad 1 "^vri-tabulate: error: diff.json: series 'a' takes either runs with a step or one run without\$" -- \
    "$bin/vri-tabulate" --layout convergence --point a 0.1 diff.json --point a - diff.json -o t.md
bad 1 '^vri-tabulate: error: --points belongs to --layout convergence$' -- \
    "$bin/vri-tabulate" --layout matrix --value x --cell a b diff.json --points p.csv -o t.md
bad 1 '^vri-tabulate: error: --layout convergence needs --point SERIES H DIFF \[STATS\]$' -- \
    "$bin/vri-tabulate" --layout convergence -o t.md
bad 1 '^vri-plot: error: nokept.yaml:2:[0-9]+: series\[0\].label_from: no row of .*points.csv is kept to take the label from$' -- \
    "$bin/vri-plot" nokept.yaml -o ../f.png
bad 1 '^vri-plot: error: both.yaml:2:[0-9]+: series\[0\] takes label or label_from, not both$' -- \
    "$bin/vri-plot" both.yaml -o ../f.png
bad_done

# Elsewhere, with --allow-dirty, and from a clean tree it runs; the manifest and gallery say which commit.
"$bin/vri-run" --results elsewhere experiments/tiny.yaml 2> /dev/null
"$bin/vri-run" --allow-dirty experiments/tiny.yaml 2> /dev/null
grep -q '"modified_files": true' results/tiny/manifest.json || fail "a dirty run's manifest does not say so"
git_q commit -q -am "the change"
git_q add results && git_q commit -q -m results
# Results that change do not make the tree dirty: they are what vri-run writes.
"$bin/vri-run" --force --gallery results experiments/tiny.yaml 2> /dev/null
head=$(git rev-parse HEAD)
grep -q '"modified_files": false' results/tiny/manifest.json || fail "a clean run's manifest says modified"
grep -q "commit \`${head:0:12}\`, manifest" results/README.md || fail "the gallery does not name commit ${head:0:12}"
echo "clean-tree checks passed"
