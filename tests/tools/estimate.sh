#!/usr/bin/env bash
# vri-run --estimate: an experiment run once is priced from its manifest, step by step (the seconds are the
# manifest's own); a step whose arguments changed since, or a new one, is counted as unpriced; an experiment
# without a manifest is said to have none; and --estimate runs and writes nothing.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
bin=${VRI_BIN:?}

printf 'points:\n  - [0.0, 0.0, 0.0, 0.0, 0.0]\n  - [1.0, 1.0, 0.2, 0.1, 0.8]\n' > red.yaml
experiment() {  # $1: the image width
    cat <<YAML
name: small
title: One scene, two placements
paper: {paper: none, item: test, says: a test}
scenes:
  red: {field: linear, field_dims: [5, 5, 5], convention: node, tf: red.yaml, size: [$1, 16]}
methods:
  riemann: {placement: [entry, entry-exit-corner], rate: 1}
comparisons:
  vs-corner: {reference: riemann-entry-exit-corner}
YAML
}
experiment 24 > exp.yaml

"$bin/vri-run" --estimate --results out exp.yaml > none.md
grep -q '^| small (no manifest) | 3 | 3 | 0.0 | 0.0 % |' none.md || fail "no manifest: $(cat none.md)"
[ ! -e out ] || fail "--estimate wrote something"

"$bin/vri-run" --results out exp.yaml 2> run.log
manifest_seconds=$(/usr/bin/python3 -c '
import json, sys
print("%.1f" % sum(s["wall_seconds"] for s in json.load(open(sys.argv[1]))["steps"]))' out/small/manifest.json)
"$bin/vri-run" --estimate --results out exp.yaml > priced.md
grep -q "^| small | 3 | 0 | $manifest_seconds | 100.0 % |" priced.md || fail "priced ($manifest_seconds s): $(cat priced.md)"
grep -q '^From nothing, one step at a time: [0-9.]* s\.$' priced.md || fail "total: $(cat priced.md)"
grep -q 'unpriced\|no price' <(tail -n 2 priced.md) && fail "all steps are priced: $(cat priced.md)"

# A wider image changes both renders' arguments; the diff's arguments stay, so it keeps its price.
experiment 32 > exp.yaml
"$bin/vri-run" --estimate --results out exp.yaml > changed.md
grep -q '^| small | 3 | 2 | ' changed.md || fail "changed: $(cat changed.md)"
grep -q '^From nothing, one step at a time: at least ' changed.md || fail "changed total: $(cat changed.md)"
grep -q '^2 steps are new or changed' changed.md || fail "changed note: $(cat changed.md)"
echo "estimate: all checks passed"
