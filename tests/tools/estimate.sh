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

# Where the files lie does not change a price: from another folder every command names the transfer
# function, the results and the tools by other paths, and every step keeps its price.
experiment 24 > exp.yaml
"$bin/vri-run" --results out exp.yaml 2> /dev/null
mkdir -p elsewhere
(cd elsewhere && "$bin/vri-run" --estimate --results ../out ../exp.yaml > ../moved.md)
grep -q "^| small | 3 | 0 | " moved.md || fail "moved: $(cat moved.md)"

# A dataset catalog among the files (experiments/*.yaml names experiments/datasets.yaml) is skipped with a note.
printf 'datasets:\n  - {name: x, file: x_2x2x2_uint8.raw, bytes: 8, sha512: "00"}\n' > datasets.yaml
"$bin/vri-run" --estimate --results out datasets.yaml exp.yaml > both.md 2> both.txt
grep -q "^vri-run: datasets.yaml is the dataset catalog, not an experiment: skipped$" both.txt || fail "$(cat both.txt)"
grep -q "^| small | 3 | 0 | " both.md || fail "with the catalog: $(cat both.md)"
echo "estimate: all checks passed"
