#!/usr/bin/env bash
# Links in a results tree (issue 48, class 1): vri-run keeps its own files in <results>/<experiment>/.steps/
# (records, logs, the Slurm executor's job files, which it deletes recursively) and never writes or deletes
# through a symbolic link there, which a results folder copied from elsewhere may hold: a .steps that is a link,
# or is not a folder, stops the run with one line before anything is written; a link in place of a step's log
# or record is removed, its target left as it was.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
bin=$VRI_BIN
cat > tf.yaml <<'YAML'
points:
  - [0.0, 0.0, 0.0, 0.0, 0.0]
  - [1.0, 1.0, 0.2, 0.1, 0.8]
YAML
cat > exp.yaml <<'YAML'
name: small
title: One render
paper: {paper: none, item: test, says: a test}
scenes: {red: {field: linear, field_dims: [5, 5, 5], convention: node, tf: tf.yaml, size: [8, 6]}}
methods: {riemann: {rate: 1}}
YAML
mkdir -p victim/slurm results/small
echo "keep me" > victim/keep.txt
echo "keep me too" > victim/slurm/job.out
echo "precious" > victim/riemann.log
snapshot() { find victim -printf '%p %s %T@\n' | sort; cat victim/keep.txt victim/slurm/job.out victim/riemann.log; }
before=$(snapshot)

# .steps a link to another folder: refused, one line, nothing written there.
ln -s ../../victim results/small/.steps
rc=0
"$bin/vri-run" --results results exp.yaml > out.txt 2> err.txt || rc=$?
[ "$rc" -eq 1 ] || fail ".steps a link: exit $rc, expected 1 ($(cat err.txt))"
[ "$(wc -l < err.txt)" -eq 1 ] && grep -Eq "^vri-run: error: (.*/)?results/small/\.steps: is a symbolic link \(to \.\./\.\./victim\); vri-run keeps its own files there and will not write or delete through a link: remove it$" err.txt ||
  fail ".steps a link: $(cat err.txt)"
[ "$(snapshot)" == "$before" ] || fail "the link's target changed: $(snapshot)"
[ ! -e results/small/riemann.exr ] || fail "a step ran although .steps is a link"

# .steps a file: refused the same way.
rm results/small/.steps && echo "not a folder" > results/small/.steps
rc=0
"$bin/vri-run" --results results exp.yaml > out.txt 2> err.txt || rc=$?
[ "$rc" -eq 1 ] && grep -Eq "^vri-run: error: (.*/)?results/small/\.steps: is not a folder; vri-run keeps its own files there: remove it$" err.txt ||
  fail ".steps a file: exit $rc, $(cat err.txt)"

# A link in place of the step's log and record, inside a real .steps: removed, their targets untouched, the
# run as without them.
rm results/small/.steps && mkdir results/small/.steps
ln -s ../../../victim/riemann.log results/small/.steps/riemann.log
ln -s ../../../victim/keep.txt results/small/.steps/riemann.json
"$bin/vri-run" --results results exp.yaml > out.txt 2> err.txt || fail "the run with links in .steps failed: $(cat err.txt)"
[ "$(snapshot)" == "$before" ] || fail "a link's target in .steps changed: $(snapshot)"
[ ! -L results/small/.steps/riemann.log ] && [ ! -L results/small/.steps/riemann.json ] && [ -f results/small/.steps/riemann.json ] ||
  fail "the links in .steps: $(ls -la results/small/.steps)"
[ -s results/small/riemann.exr ] || fail "the step did not run"
echo "links in results trees: all checks passed"
