#!/usr/bin/env bash
# vri-run --executor slurm against a real single-node Slurm cluster (tests/tools/lib/slurm_cluster.sh):
# images and every other output bitwise those of --executor local and manifests equal but for where and
# when steps ran; a tiled render merges bitwise into the untiled image on both executors; dependencies
# respected (no diff starts before its renders end); a job cancelled with scancel fails its step and its
# dependents with the job's id and state, and a rerun completes; SIGTERM to vri-run cancels its jobs and
# leaves no partial output; bundled steps share jobs; a volume's bricks each run in a job of their own and
# join as locally; a results folder or a tool the compute node does not see as vri-run does is refused
# before anything is submitted.
source "$(dirname "${BASH_SOURCE[0]}")/lib/slurm_cluster.sh"
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
bin=${VRI_BIN:?}
python=/usr/bin/python3
start_slurm_cluster "$PWD/cluster"

# tf.yaml, and slow.yaml for the cases of a slow render (about 15 s) and a diff that needs it, further down.
source "$(dirname "${BASH_SOURCE[0]}")/lib/slurm_slow_study.sh"
write_slow_study 400000
# Two placements and the exact method on the linear field, a diff of each against the corner placement,
# a table of the diffs: every kind of step and a dependency between them.
# An outside renderer (the scene card's example, through vri-outside) runs on the nodes like vri's own steps.
cat > exp.yaml <<YAML
name: small
title: A small study on the test cluster
paper: {paper: A, item: Fig. 4, says: a test}
scenes:
  cube: {field: linear, field_dims: [5, 5, 5], convention: node, tf: tf.yaml, size: [40, 30],
         camera: {eye: [-8, 4, 1], target: [0, 0, 0], up: [0, 0, 1]}}
renderers:
  card-example: {command: [$python, $VRI_SOURCE/examples/scene_card/render_from_card.py, "{card}", "{output}"], image: f32}
methods:
  card: {renderer: card-example, placement: entry, rate: 2, precision: double}
  riemann: {placement: [entry, entry-exit-corner], rate: 2}
  exact: {eps: 1e-6}
  exact-tiled: {method: exact, eps: 1e-6, tiles: 3}   # three tile jobs and a merge
comparisons:
  vs-corner: {reference: riemann-entry-exit-corner, diff_image: png}
tables:
  metrics: {title: "against the corner placement", comparisons: [vs-corner]}
YAML
summary() { grep "vri-run: small:" "$1"; }
slurm=("$bin/vri-run" --executor slurm --slurm-poll 0.2)

# The same study on both executors, into the same results path one after the other.
"$bin/vri-run" --results res exp.yaml 2> local.txt || { cat local.txt; fail "the local run failed"; }
mv res local
# A job per step, one CPU each: on the two CPUs of the test node, a diff could start beside a render if
# nothing held it back but its dependency.
"${slurm[@]}" --slurm-bundle 0 --slurm-cpus 1 --results res exp.yaml 2> slurm.txt || { cat slurm.txt; fail "the Slurm run failed"; }
summary slurm.txt | grep -q "steps, [1-9][0-9]* ran, 0 cached" || { cat slurm.txt; fail "the Slurm run ran nothing"; }
grep -q "steps in Slurm jobs [0-9-]* ([0-9]* jobs)" slurm.txt || { cat slurm.txt; fail "the Slurm run did not say which jobs it submitted"; }
# Images bitwise (pixels: a header holds its provenance, with times), PNGs and tables byte for byte.
same_outputs() {  # same_outputs DIR-A DIR-B
    local file name
    for file in "$1"/*; do
        name=$(basename "$file")
        case "$name" in
            *.exr) "$bin/vri-diff" "$file" "$2/$name" --fail 0 > /dev/null || fail "$name: pixels differ between $1 and $2" ;;
            *.png|*.csv|*.md) cmp "$file" "$2/$name" || fail "$name differs between $1 and $2" ;;
        esac
    done
}
same_outputs local/small res/small
# A full disk while the node check is written (a file size limit below the check's list of tools and inputs):
# one line, and no part of the check left in the results root.
if bash -c 'ulimit -f 2 && exec "$@"' limited "${slurm[@]}" --results res-full exp.yaml 2> full.txt; then
    fail "the Slurm run wrote past the limit"
fi
grep -q "^vri-run: error: .*/res-full/\.slurm-check/[0-9a-f]*\.json: cannot write: File too large$" full.txt || { cat full.txt; fail "the full disk was not named"; }
[ ! -e res-full/.slurm-check ] || fail "the node check's files were left: $(ls -A res-full/.slurm-check)"
# The tiled exact image is the untiled one, bit for bit, on both executors.
for dir in local res; do
    "$bin/vri-diff" $dir/small/exact.exr $dir/small/exact-tiled.exr --fail 0 > /dev/null || fail "$dir: the tiled image differs from the untiled one"
done
# A volume as bricks (issue 49): each brick a job of its own, the join's image bitwise the local run's and
# within its bound of the unbricked image.
source "$(dirname "${BASH_SOURCE[0]}")/lib/blob.sh" && write_blob_volume
cat > bricks.yaml <<'YAML'
name: bricks
title: A volume as bricks on the test cluster
paper: {paper: A, item: none, says: a test}
scenes:
  blob: {volume: blob_8x8x8_uint8.raw, convention: cell, tf: tf.yaml, size: [31, 23],
         camera: {eye: [20, -14, 17], target: [4, 4, 4], up: [0, 0, 1]}}
methods:
  whole: {method: riemann, step: 0.5}
  bricked: {method: riemann, step: 0.5, bricks: [2, 2, 2]}
YAML
"$bin/vri-run" --results local bricks.yaml 2> bricks-local.txt || { cat bricks-local.txt; fail "the local bricked run failed"; }
"${slurm[@]}" --results res bricks.yaml 2> bricks-slurm.txt || { cat bricks-slurm.txt; fail "the Slurm bricked run failed"; }
"$bin/vri-diff" local/bricks/bricked.exr res/bricks/bricked.exr --fail 0 > /dev/null || fail "the joined bricks differ between executors"
"$python" - res/bricks local/bricks <<'PY' || fail "the bricks on Slurm"
import glob, json, sys
steps = json.load(open(sys.argv[1] + "/manifest.json"))["steps"]
jobs = [s["execution"]["job_id"] for s in steps if ".brick-" in s["id"]]
assert len(jobs) == 8 and len(set(jobs)) == 8, ("each brick a job of its own", jobs)
# Each brick took its volume's digest from vri-run's record (util/input_digest.h), on either executor.
for results in sys.argv[1:]:
    layers = glob.glob(results + "/bricked.brick-*.json")
    assert len(layers) == 8, layers
    for layer in layers:
        source = json.load(open(layer)).get("input_digests_from", "")
        assert source.endswith("/bricks/.steps/input-digests.json"), (layer, source)
PY
# --slurm-max-jobs 2: two jobs at a time, the next submitted as one ends; the same images.
"${slurm[@]}" --slurm-max-jobs 2 --results capped bricks.yaml 2> capped.txt || { cat capped.txt; fail "the capped Slurm run failed"; }
grep -q "steps in Slurm jobs [0-9-]* (2 jobs), [0-9]* more as these end (--slurm-max-jobs)$" capped.txt ||
    { cat capped.txt; fail "the capped run did not say it held jobs back"; }
grep -q "submitted Slurm jobs" capped.txt || { cat capped.txt; fail "the capped run submitted no job later"; }
"$bin/vri-diff" local/bricks/bricked.exr capped/bricks/bricked.exr --fail 0 > /dev/null || fail "the capped run's image differs"
# Manifests: equal but for hosts, job ids, times (the stats files hold the frame times, so their digests
# differ too) and the executor; every Slurm step names its job.
"$python" - local/small/manifest.json res/small/manifest.json <<'PY' || fail "the manifests differ beyond where and when"
import json, sys
def strip(m):
    m.pop("machine")
    for s in m["steps"]:
        for k in ("execution", "wall_seconds", "ran_utc"):
            s.pop(k)
        for f in s["inputs"] + s["outputs"]:
            if f["path"].endswith(".json"):
                f.pop("sha512")
    return m
local, slurm = (json.load(open(p)) for p in sys.argv[1:])
for s in slurm["steps"]:
    e = s["execution"]
    assert e["executor"] == "slurm" and e["job_id"].isdigit() and e["job_state"] == "COMPLETED" and e["node"], e
assert all(s["execution"]["executor"] == "local" for s in local["steps"])
# What differs, said: a key's values in both, "-" where one lacks it.
def differences(x, y):
    return "; ".join(f"{k}: local {x.get(k, '-')!r}, Slurm {y.get(k, '-')!r}"
                     for k in sorted(set(x) | set(y)) if k not in x or k not in y or x[k] != y[k])
a, b = strip(local), strip(slurm)
if len(a["steps"]) != len(b["steps"]):
    sys.exit(f"{len(a['steps'])} steps locally, {len(b['steps'])} on Slurm")
for x, y in zip(a["steps"], b["steps"]):
    if x != y:
        sys.exit(f"step {x['id']}: {differences(x, y)}")
if a != b:
    sys.exit(differences(a, b))
PY

# Dependencies: with a job per step, every diff started after the renders it compares had ended.
"$python" - res/small <<'PY' || fail "a step started before a step it depends on ended"
import json, sys, glob, os
d = sys.argv[1]
status = {os.path.basename(p)[:-len(".status.json")]: json.load(open(p)) for p in glob.glob(d + "/.steps/*.status.json")}
manifest = json.load(open(d + "/manifest.json"))
writer = {o["path"]: s["id"] for s in manifest["steps"] for o in s["outputs"]}
checked = 0
for s in manifest["steps"]:
    for i in s["inputs"]:
        if i["path"] in writer:
            up = status[writer[i["path"]]]
            assert status[s["id"]]["started_epoch"] >= up["ended_epoch"], (s["id"], writer[i["path"]])
            checked += 1
assert checked >= 4, checked
PY

# Nothing changed: a second Slurm run submits nothing; a local run then finds everything cached too.
"${slurm[@]}" --results res exp.yaml 2> again.txt || { cat again.txt; fail "the cached Slurm run failed"; }
summary again.txt | grep -q ", 0 ran," || { cat again.txt; fail "a cached step ran again on Slurm"; }
jobs_before=$(squeue --noheader --states=all --format=%i | wc -l)
"${slurm[@]}" --results res exp.yaml 2> again.txt || { cat again.txt; fail "the cached Slurm run failed"; }
[ "$(squeue --noheader --states=all --format=%i | wc -l)" -eq "$jobs_before" ] || fail "a fully cached run submitted a job"

# Two files in one vri-run: both files' jobs are submitted before either is waited for, and each gets
# its own manifest with the local run's images.
sed 's/^name: small$/name: small2/' exp.yaml > exp2.yaml
"${slurm[@]}" --results both exp.yaml exp2.yaml 2> both.txt || { cat both.txt; fail "the two-file Slurm run failed"; }
last_submitted=$(grep -n "steps in Slurm jobs" both.txt | tail -1 | cut -d: -f1)
first_done=$(grep -n "steps, [0-9]* ran" both.txt | head -1 | cut -d: -f1)
[ "$(grep -c "steps in Slurm jobs" both.txt)" -eq 2 ] && [ "$last_submitted" -lt "$first_done" ] ||
    { cat both.txt; fail "the second file's jobs waited for the first file's"; }
same_outputs local/small both/small
same_outputs local/small both/small2
[ -s both/small/manifest.json ] && [ -s both/small2/manifest.json ] || fail "a manifest is missing after the two-file run"
# One file fails (a command exits 64 on its node): the other still completes with its manifest.
cat > failing.yaml <<'YAML'
name: failing
title: A command that fails on its node
paper: {paper: A, item: Fig. 4, says: a test}
scenes:
  cube: {field: linear, field_dims: [5, 5, 5], convention: node, tf: tf.yaml, size: [40, 30]}
methods:
  riemann: {placement: [entry-exit-corner], rate: 2}
commands:
  broken: {tool: vri-tf, options: {samples: 0}, outputs: {o: broken.csv}}
YAML
if "${slurm[@]}" --results mixed failing.yaml exp2.yaml 2> mixed.txt; then fail "a run with a failing step exited 0"; fi
grep -q "vri-run: error: failing: step 'broken' failed (exit status 64) in Slurm job [0-9]* FAILED" mixed.txt ||
    { cat mixed.txt; fail "the failure does not name its experiment, step, job and state"; }
[ -s mixed/small2/manifest.json ] && [ ! -e mixed/failing/manifest.json ] || fail "manifests after a failed experiment"
same_outputs local/small mixed/small2

# Bundled: the cheap steps of a priced plan share jobs (the default bundle of 60 s holds them all), but for the
# three tiles of exact-tiled, each in a job of its own so that they run side by side: the steps before them
# in one job, each tile in one, the merge and the steps after it in one.
"${slurm[@]}" --force --results res exp.yaml 2> bundled.txt || { cat bundled.txt; fail "the bundled run failed"; }
steps=$(summary bundled.txt | sed -n 's/.*: \([0-9]*\) steps, .*/\1/p')
grep -q "^vri-run: small: $steps steps in Slurm jobs [0-9]*-[0-9]* (5 jobs)$" bundled.txt ||
    { cat bundled.txt; fail "the priced steps were not bundled around the tiles"; }
for k in 1 2 3; do
    grep -q "ran vri-reference exact-tiled.tile-$k .*job [0-9]* " bundled.txt || { cat bundled.txt; fail "tile $k did not run"; }
done
[ "$(grep -o "ran vri-reference exact-tiled.tile-[0-9] ([0-9.]* s, job [0-9]*" bundled.txt | sed 's/.*job //' | sort -u | wc -l)" -eq 3 ] ||
    { cat bundled.txt; fail "two tiles shared a job"; }
same_outputs local/small res/small

# The slow study (write_slow_study above).
no_partial_outputs() {
    ! ls res/slow/"$slow_step".* > /dev/null 2>&1 || fail "the cancelled render left an output"
    [ -z "$(find res/slow -name '*.tmp.*')" ] || fail "a temporary file was left: $(find res/slow -name '*.tmp.*')"
}

# scancel of the slow job: its step fails naming the job and its state, the diff after it does not run.
cancel_slow() { scancel "$job"; }
interrupt_slow cancelled.txt cancel_slow
[ "$status" -ne 0 ] || fail "vri-run succeeded although its job was cancelled"
grep -q "step '$slow_step' failed: Slurm job $job CANCELLED" cancelled.txt ||
    { cat cancelled.txt; fail "no line naming the cancelled job and its state"; }
[ ! -e res/slow/vs-fine-riemann-entry-exit-corner-r2.json ] || fail "the diff ran although its render was cancelled"
[ ! -e res/slow/manifest.json ] || fail "a failed run wrote a manifest"
no_partial_outputs

# SIGTERM to vri-run: every job it submitted is cancelled, and nothing is left half-written.
terminate_run() { kill -TERM "$run"; }
interrupt_slow terminated.txt terminate_run
[ "$status" -ne 0 ] || fail "vri-run exited 0 after SIGTERM"
grep -q "interrupted by SIGTERM; cancelled Slurm jobs [0-9,-]* ([0-9]* jobs\?)" terminated.txt || { cat terminated.txt; fail "SIGTERM did not say what it cancelled"; }
[ -z "$(squeue --noheader --states=PENDING,RUNNING,COMPLETING --format=%i)" ] || { squeue; fail "jobs are left after SIGTERM"; }
no_partial_outputs

# A job that cannot start (held an hour: squeue's reason BeginTime, as a partition down or a drained node
# would hold it): a line says why it pends, --slurm-max-pending gives up and cancels it, and nothing is left.
if "${slurm[@]}" --slurm-arg=--begin=now+1hour --slurm-max-pending 3 --results pend exp.yaml 2> pending.txt; then
    fail "vri-run succeeded although its job could not start"
fi
grep -q "^vri-run: the Slurm check job [0-9]*: 1 job pending (squeue's reason: BeginTime) for [0-9.]* s, none running$" pending.txt ||
    { cat pending.txt; fail "no line saying why the job pends"; }
grep -q "^vri-run: error: the Slurm check job [0-9]*: 1 job pending (squeue's reason: BeginTime) for [0-9.]* s, none running: gave up after --slurm-max-pending 3 s; cancelled Slurm jobs [0-9]* (1 job)$" pending.txt ||
    { cat pending.txt; fail "--slurm-max-pending did not give up with the reason"; }
[ -z "$(squeue --noheader --states=PENDING,RUNNING,COMPLETING --format=%i)" ] || { squeue; fail "a job is left after giving up"; }

# SIGKILL to vri-run leaves its jobs in the queue; the rerun below cancels them before it submits its own,
# so that no copy of a step runs beside another. A rerun completes, running only what is missing (the fast
# render was cached by the runs above). (Where the slow render's job ended by itself, before the kill or
# before the rerun cancelled it, as on a loaded machine it may, the case runs again.)
for attempt in 1 2 3; do
    start_slow killed.txt
    orphan=$job
    kill -KILL "$run"
    wait "$run" 2> /dev/null || true
    if [ -n "$(squeue --noheader --states=PENDING,RUNNING --jobs="$orphan" --format=%i 2> /dev/null || true)" ]; then
        "${slurm[@]}" --results res slow.yaml 2> rerun.txt || { cat rerun.txt; fail "the rerun failed"; }
        [ "$(squeue --noheader --states=all --jobs="$orphan" --format=%T)" = COMPLETED ] || break
    fi
    [ "$attempt" -lt 3 ] || fail "the killed run's job $orphan ended by itself in each of three attempts"
    echo "note: the slow render's job $orphan ended by itself before the rerun could cancel it (attempt $attempt)"
    clear_slow
done
grep -q "^vri-run: slow: cancelling Slurm jobs [0-9,-]* ([0-9]* jobs\?) of an earlier vri-run on this results folder, still in the queue$" rerun.txt ||
    { cat rerun.txt; fail "the rerun did not cancel the killed run's jobs"; }
[ "$(squeue --noheader --states=all --jobs="$orphan" --format=%T)" = CANCELLED ] ||
    { squeue --states=all; fail "the killed run's job $orphan was not cancelled"; }
# The job outputs of the runs before stay (an error message may name one), those of the last three runs only.
runs_kept=$(ls res/slow/.steps/slurm | sed -n 's/^job-\([0-9a-f]*\)-[0-9]*\.out$/\1/p' | sort -u | wc -l)
[ "$runs_kept" -eq 3 ] || { ls res/slow/.steps/slurm; fail "the job outputs of $runs_kept runs were kept, not 3"; }
summary_slow=$(grep "vri-run: slow:" rerun.txt)
[[ $summary_slow == *"3 steps, 2 ran, 1 cached"* ]] || { cat rerun.txt; fail "the rerun did not run just what was missing"; }
"$bin/vri-run" --results local slow.yaml 2> /dev/null
same_outputs local/slow res/slow

# What the compute node does not see as vri-run does is refused before anything is submitted. vri-run
# runs in a mount namespace of its own (unshare), where a path shows something else than on the node.
if unshare --mount --propagation private true 2> /dev/null; then
    # The results folder: vri-run sees a fresh tmpfs where the node sees the scratch folder's own.
    mkdir -p hidden
    if unshare --mount --propagation private sh -c 'mount -t tmpfs none "$1" && shift && exec "$@"' sh "$PWD/hidden" \
        "${slurm[@]}" --results "$PWD/hidden" exp.yaml 2> unshared.txt; then
        fail "vri-run ran on a results folder the compute node does not see"
    fi
    [ "$(wc -l < unshared.txt)" -eq 1 ] || { cat unshared.txt; fail "the refusal is not one line"; }
    grep -q "/hidden: the Slurm check job could not leave its report in this results folder" unshared.txt || { cat unshared.txt; fail "the refusal does not name the results folder"; }
    # A tool: vri-run's vri-diff differs from the one the node runs.
    renders_before=$(squeue --noheader --states=all --name=vri:small:riemann-entry --format=%i | wc -l)
    mkdir -p tools && cp "$bin"/vri-* tools/ && cp tools/vri-diff changed-vri-diff && echo >> changed-vri-diff
    if unshare --mount --propagation private sh -c 'mount --bind "$1" "$2" && shift 2 && exec "$@"' sh \
        "$PWD/changed-vri-diff" "$PWD/tools/vri-diff" tools/vri-run --executor slurm --slurm-poll 0.2 --slurm-bundle 0 --results res2 exp.yaml 2> tool.txt; then
        fail "vri-run ran with a tool the compute node sees differently"
    fi
    grep -q "tools/vri-diff: differs on node .* from vri-run's host" tool.txt || { cat tool.txt; fail "the refusal does not name the tool"; }
    [ "$(wc -l < tool.txt)" -eq 1 ] || { cat tool.txt; fail "the refusal is not one line"; }
    [ "$(squeue --noheader --states=all --name=vri:small:riemann-entry --format=%i | wc -l)" -eq "$renders_before" ] ||
        fail "jobs were submitted although the check failed"
else
    echo "note: unshare cannot make a mount namespace here: the cases of paths the node does not share are not run"
fi
# Options vri-run sets itself are refused, from the command line and from the site's variable.
if "${slurm[@]}" --slurm-arg=--dependency=afterok:1 --results res exp.yaml 2> bad.txt; then fail "--slurm-arg=--dependency accepted"; fi
grep -q "^vri-run: error: --slurm-arg: '--dependency=afterok:1': vri-run sets --dependency itself" bad.txt || { cat bad.txt; fail "no line for --dependency"; }
if VRI_SLURM_ARGS="--qos=normal -o/tmp/x" "${slurm[@]}" --results res exp.yaml 2> bad.txt; then fail "VRI_SLURM_ARGS=-o accepted"; fi
grep -q "^vri-run: error: VRI_SLURM_ARGS: '-o/tmp/x'" bad.txt || { cat bad.txt; fail "no line for -o in VRI_SLURM_ARGS"; }
# A job the cluster cannot hold (more CPUs than its node has): this cluster takes it and leaves it pending
# (squeue's reason PartitionConfig), which vri-run says, and gives up on with --slurm-max-pending.
if "${slurm[@]}" --slurm-cpus 1024 --slurm-max-pending 2 --results refused slow.yaml 2> refused.txt; then
    fail "a job of 1024 CPUs ran"
fi
grep -q "^vri-run: error: Slurm jobs: [0-9]* jobs\? pending (squeue's reason: PartitionConfig.*gave up after --slurm-max-pending 2 s; cancelled Slurm jobs" refused.txt ||
    { cat refused.txt; fail "the jobs the cluster cannot hold were not given up on with their reason"; }
[ -z "$(squeue --noheader --states=PENDING,RUNNING,COMPLETING --format=%i)" ] || { squeue; fail "a job is left after giving up"; }
echo "slurm: OK"
