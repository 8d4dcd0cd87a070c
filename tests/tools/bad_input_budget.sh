#!/usr/bin/env bash
# Bad input to vri-run --estimate: --estimate with --dry-run is bad usage (64); a manifest that is not one is one
# line naming it (1); nothing is written either way.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
source "$(dirname "${BASH_SOURCE[0]}")/lib/bad_input.sh"
printf 'points:\n  - [0.0, 0.0, 0.0, 0.0, 0.0]\n  - [1.0, 1.0, 0.2, 0.1, 0.8]\n' > red.yaml
cat > exp.yaml <<'YAML'
name: small
title: One render
paper: {paper: none, item: test, says: a test}
scenes:
  red: {field: linear, field_dims: [5, 5, 5], convention: node, tf: red.yaml, size: [8, 6]}
methods:
  riemann: {rate: 1}
YAML
mkdir -p out/small
printf '{"steps": [{"id": "riemann", "command": "x"}]}\n' > out/small/manifest.json

bad 64 '^vri-run: error: --dry-run excludes --estimate' -- "$VRI_BIN/vri-run" --estimate --dry-run exp.yaml
bad 64 "^vri-run: error: --jobs: expected a whole number from 1 to 64, got '0'" -- "$VRI_BIN/vri-run" --dry-run --jobs 0 exp.yaml
bad 1 '^vri-run: error: .*out/small/manifest.json: .*wall_seconds' -- "$VRI_BIN/vri-run" --estimate --results out exp.yaml
printf 'not json\n' > out/small/manifest.json
bad 1 '^vri-run: error: .*out/small/manifest.json' -- "$VRI_BIN/vri-run" --estimate --results out exp.yaml
bad_done
