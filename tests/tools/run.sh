#!/usr/bin/env bash
# vri-run end to end: the --dry-run commands reproduce its results by hand, a second run is all
# cached, a changed transfer function re-runs only what depends on it, a failing step stops the run
# with its command and output, a command's Markdown shows in the gallery, and a malformed file is one
# line with file:line:col.
set -euo pipefail
bin=${VRI_BIN:?} dir=${VRI_SCRATCH:?}
rm -rf "$dir" && mkdir -p "$dir" && cd "$dir"

cat > red.yaml <<'YAML'
points:
  - [0.0, 0.0, 0.0, 0.0, 0.0]
  - [1.0, 1.0, 0.2, 0.1, 0.8]
YAML
cat > blue.yaml <<'YAML'
points:
  - [0.0, 0.0, 0.0, 0.0, 0.0]
  - [1.0, 0.1, 0.2, 1.0, 0.8]
YAML
cat > exp.yaml <<'YAML'
name: small
title: Two scenes, two placements
paper: {paper: A, item: Fig. 4, says: a test}
scenes:
  red:  {field: linear, field_dims: [5, 5, 5], convention: node, tf: red.yaml, size: [24, 16],
         camera: {eye: [-8, 4, 1], target: [0, 0, 0], up: [0, 0, 1]}}
  blue: {field: linear, field_dims: [5, 5, 5], convention: node, tf: blue.yaml, size: [24, 16]}
methods:
  riemann: {placement: [entry, entry-exit-corner], rate: 1}
comparisons:
  vs-corner-red: {reference: red-riemann-entry-exit-corner, diff_image: png, diff_scale: 4}
  vs-corner-blue: {reference: blue-riemann-entry-exit-corner}
commands:
  rays:
    tool: vri-rays2d
    options: {convention: node, rates: [1, 4]}
    outputs: {o: rays.csv, errors: errors.md}
YAML
summary() { grep "vri-run: small:" "$1"; }

# The printed commands, run by hand, give what vri-run gives.
"$bin/vri-run" --dry-run --results hand exp.yaml > commands.sh
[ "$(wc -l < commands.sh)" -eq 7 ] || { echo "expected 7 commands"; cat commands.sh; exit 1; }
grep -q -- "vri-rays2d --convention node --rates 1,4 -o hand/small/rays.csv --errors hand/small/errors.md" commands.sh
[ ! -e hand ] || { echo "--dry-run wrote something"; exit 1; }
# On Slurm: each job's steps and its sbatch command, a job it waits for named; nothing submitted or written.
"$bin/vri-run" --dry-run --executor slurm --results hand exp.yaml > jobs.txt
[ "$(grep -c '^sbatch --parsable --job-name=vri:small:' jobs.txt)" -eq "$(grep -c '^# small: job ' jobs.txt)" ] ||
  { echo "a job without its sbatch line"; cat jobs.txt; exit 1; }
grep -q "^# small: job [0-9]* of [0-9]*: vs-corner-red-riemann-entry" jobs.txt || { cat jobs.txt; exit 1; }
grep -q "'--dependency=afterok:<job [0-9]*>:<job [0-9]*>" jobs.txt || { echo "no dependency named"; cat jobs.txt; exit 1; }
[ ! -e hand ] || { echo "--dry-run --executor slurm wrote something"; exit 1; }
# A site profile: its options on every job, its kinds' resources on their steps' jobs, the command line's last.
cat > profile.yaml <<'YAML'
account: proj123
qos: long
args: [--exclusive]
cpus: 3
kinds:
  render: {cpus: 6, mem: 2G, time: 45}
  diff: {mem: 700M}
YAML
VRI_SLURM_PROFILE=profile.yaml "$bin/vri-run" --dry-run --executor slurm --slurm-arg=--qos=short --results hand exp.yaml > jobs.txt
grep "^sbatch" jobs.txt | grep -v -- "--account=proj123 --qos=long --exclusive --qos=short" && { echo "a job without the profile's options, then the command line's"; cat jobs.txt; exit 1; }
grep "vri:small:red-riemann-entry " jobs.txt | grep -q -- "--cpus-per-task=6 --mem=2048M --time=45" || { cat jobs.txt; exit 1; }
grep "vri:small:vs-corner-red" jobs.txt | grep -q -- "--cpus-per-task=1 --mem=700M " || { cat jobs.txt; exit 1; }
grep "vri:small:rays" jobs.txt | grep -q -- "--cpus-per-task=3 " || { echo "the profile's cpus"; cat jobs.txt; exit 1; }
VRI_SLURM_PROFILE=profile.yaml "$bin/vri-run" --dry-run --executor slurm --slurm-cpus 2 --results hand exp.yaml > jobs.txt
grep "vri:small:rays" jobs.txt | grep -q -- "--cpus-per-task=2 " || { echo "--slurm-cpus over the profile's"; cat jobs.txt; exit 1; }
printf 'kinds:\n  renders: {cpus: 2}\n' > bad-profile.yaml
set +e; VRI_SLURM_PROFILE=bad-profile.yaml "$bin/vri-run" --dry-run --executor slurm --results hand exp.yaml 2> bad.txt; rc=$?; set -e
[ "$rc" -eq 1 ] && grep -q "^vri-run: error: bad-profile.yaml:2:3: unknown kind of step 'renders'" bad.txt || { cat bad.txt; exit 1; }
printf 'args: [--output=x]\n' > bad-profile.yaml
set +e; VRI_SLURM_PROFILE=bad-profile.yaml "$bin/vri-run" --dry-run --executor slurm --results hand exp.yaml 2> bad.txt; rc=$?; set -e
[ "$rc" -eq 1 ] && grep -q "^vri-run: error: bad-profile.yaml:1:8: .*--output" bad.txt || { cat bad.txt; exit 1; }
bash -e commands.sh > /dev/null
"$bin/vri-run" --jobs 3 --results auto exp.yaml 2> first.txt
summary first.txt | grep -q "7 steps, 7 ran, 0 cached" || { cat first.txt; exit 1; }
for exr in hand/small/*.exr; do "$bin/vri-diff" "$exr" "auto/small/$(basename "$exr")" --fail 0 > /dev/null; done
cmp hand/small/rays.csv auto/small/rays.csv
cmp hand/small/vs-corner-red-riemann-entry.png auto/small/vs-corner-red-riemann-entry.png
grep -q '"percent"' auto/small/vs-corner-blue-riemann-entry.json
grep -q '"wall_seconds"' auto/small/manifest.json
grep -q "vri-render" auto/small/manifest.json
# --jobs 3: a render or a command ran alone, whatever ran beside what (the manifest says, per step).
/usr/bin/python3 - auto/small/manifest.json <<'PY'
import json, sys
steps = json.load(open(sys.argv[1]))["steps"]
kind = {s["id"]: s["kind"] for s in steps}
for s in steps:
    beside = s["execution"].get("beside", [])
    if s["kind"] in ("render", "command") and beside:
        sys.exit(f"{s['id']} ran beside {beside}")
    if any(kind[b] in ("render", "command") for b in beside):
        sys.exit(f"{s['id']} ran beside a render or command: {beside}")
PY

# Nothing changed: nothing runs.
"$bin/vri-run" --results auto exp.yaml 2> second.txt
summary second.txt | grep -q "7 steps, 0 ran, 7 cached" || { cat second.txt; exit 1; }

# One transfer function changes: its scene's renders and diff run again, the other scene's do not.
sed -i 's/0.8]/0.7]/' red.yaml
"$bin/vri-run" --results auto exp.yaml 2> third.txt
summary third.txt | grep -q "7 steps, 3 ran, 4 cached" || { cat third.txt; exit 1; }

# A deleted output is made again; what reads that step's outputs is not, since the render writes the
# same bytes again (vri's EXR files hold no time stamp); --force runs everything.
cp auto/small/blue-riemann-entry.exr blue-before.exr
rm auto/small/blue-riemann-entry.png
"$bin/vri-run" --results auto exp.yaml 2> fourth.txt
summary fourth.txt | grep -q "1 ran, 6 cached" || { cat fourth.txt; exit 1; }
cmp blue-before.exr auto/small/blue-riemann-entry.exr || { echo "the same render wrote a different EXR file"; exit 1; }
"$bin/vri-run" --force --results auto exp.yaml 2> fifth.txt
summary fifth.txt | grep -q "7 ran, 0 cached" || { cat fifth.txt; exit 1; }

# A failing step: its command and its output, a non-zero exit, no record and no manifest.
head -c 100 /dev/zero > short_8x8x8_uint8.raw
sed -e 's/field: linear, field_dims: \[5, 5, 5\], convention: node, tf: blue.yaml/volume: short_8x8x8_uint8.raw, convention: cell, tf: blue.yaml/' \
    exp.yaml > failing.yaml
set +e; "$bin/vri-run" --results auto failing.yaml 2> failed.txt; rc=$?; set -e
[ "$rc" -ne 0 ] || { echo "a failing step exited 0"; exit 1; }
grep -q "step 'blue-riemann-entry' failed" failed.txt || { cat failed.txt; exit 1; }
grep -q -- "--volume short_8x8x8_uint8.raw" failed.txt || { cat failed.txt; exit 1; }
grep -q "vri-render: error: .*short_8x8x8_uint8.raw" failed.txt || { cat failed.txt; exit 1; }
# On lines of their own: the failure, the command indented under it, then the tool's own error; no escaped newline.
grep -q "^vri-run: error: step 'blue-riemann-entry' failed (exit status 1):$" failed.txt || { cat failed.txt; exit 1; }
grep -q "^  .*vri-render .*--volume short_8x8x8_uint8.raw" failed.txt || { cat failed.txt; exit 1; }
grep -q "^vri-render: error: .*short_8x8x8_uint8.raw" failed.txt || { cat failed.txt; exit 1; }
! grep -q 'x0a' failed.txt || { echo "an escaped newline in the failure"; cat failed.txt; exit 1; }
[ ! -e auto/small/.steps/blue-riemann-entry.json ] || { echo "record written for a failed step"; exit 1; }
[ ! -e auto/small/manifest.json ] || { echo "manifest left by a failed run"; exit 1; }

# A malformed experiment: one line with file:line:col, non-zero exit.
printf 'name: x\ntitle: X\npaper: {paper: A, item: I, says: S}\nscenes:\n  s: {field: linear, convention: node, tf: red.yaml, sise: [4, 4]}\nmethods: {riemann: {}}\n' > typo.yaml
set +e; "$bin/vri-run" --dry-run typo.yaml > /dev/null 2> err.txt; rc=$?; set -e
[ "$rc" -ne 0 ] && [ "$(wc -l < err.txt)" -eq 1 ] && grep -q "typo.yaml:5:54: unknown key 'sise'" err.txt || { cat err.txt; exit 1; }

# The gallery (after a good run: the failed one left no manifest) lists the experiment with its
# images and, inlined, the command's Markdown table.
"$bin/vri-run" --results auto --gallery auto exp.yaml 2> /dev/null
{ grep -q "Two scenes, two placements" auto/README.md && grep -q "small/red-riemann-entry.png" auto/README.md &&
  grep -qF "$(head -1 auto/small/errors.md)" auto/README.md; } || { cat auto/README.md; exit 1; }

grep -q "Examples" <<<"$("$bin/vri-run" --help)"
echo "run: all checks passed"
