#!/usr/bin/env bash
# vri-run --executor slurm when the test cluster fails under it (tests/tools/lib/slurm_cluster.sh, its clients
# waiting at most 3 s a message). The controller: paused (SIGSTOP) until squeue fails, vri-run says so, asks
# again and completes once it answers, its outputs those of a local run; stopped for longer than
# --slurm-max-outage, vri-run gives up with one line saying that it could not cancel its job, which may still
# run, and how to cancel it, and a rerun once the controller is back completes; SIGTERM while squeue waits on
# a paused controller stops vri-run all the same, saying the same of its job. The node: set DOWN under a
# running job, which ends NODE_FAIL (requeueing off): --slurm-retries 1 submits it again, the run completes
# with the local image and the manifest names the attempt before; without retries one line names the job.
# A job Slurm requeues after its node failed: one line says so, and the manifest names the requeue. A job its
# node cannot start (a failing prolog), which Slurm holds: cancelled as LAUNCH_FAILED, and retried. A node
# drained, and a job held: vri-run names squeue's reason and gives up after --slurm-max-pending.
# Memory: a render's job over the --mem a site profile gives it is killed by the cluster's enforcement; one line
# says OUT_OF_MEMORY with slurmstepd's words, and --slurm-retries doubles --mem until it fits.
source "$(dirname "${BASH_SOURCE[0]}")/lib/slurm_cluster.sh"
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
bin=${VRI_BIN:?}
start_slurm_cluster "$PWD/cluster" 3

# A render of several seconds and a diff that needs it (and tf.yaml, which it reads).
source "$(dirname "${BASH_SOURCE[0]}")/lib/slurm_slow_study.sh"
write_slow_study 200000
"$bin/vri-run" --results local slow.yaml 2> local.txt || { cat local.txt; fail "the local run failed"; }

# Waits (at most a minute) until FILE has a line matching PATTERN.
wait_for_line() {
    for _ in $(seq 600); do
        grep -q "$2" "$1" && return 0
        sleep 0.1
    done
    cat "$1"
    fail "no line matching '$2' in $1"
}
same_images() {
    "$bin/vri-diff" "local/slow/$slow_step.exr" "res/slow/$slow_step.exr" --fail 0 > /dev/null ||
        fail "the Slurm run's image differs from the local one"
}
controller=$(cat cluster/slurmctld.pid)
run=
# A failed check leaves neither the controller paused nor vri-run running (the cluster's own trap then stops the daemons).
leave() {
    kill -CONT "$(cat cluster/slurmctld.pid 2>/dev/null)" 2>/dev/null || true
    [ -z "$run" ] || kill "$run" 2>/dev/null || true
    stop_slurm_cluster
}
trap leave EXIT

# The controller paused until squeue fails: vri-run says so and asks again, then goes on.
start_slow paused.txt
kill -STOP "$controller"
wait_for_line paused.txt "^vri-run: squeue failed (.*; asking again for up to 120 s (--slurm-max-outage) while the jobs run on$"
kill -CONT "$controller"
wait "$run" || { cat paused.txt; fail "vri-run failed after the controller answered again"; }
grep -q "^vri-run: squeue answers again after [0-9.]* s$" paused.txt || { cat paused.txt; fail "no line saying squeue answers again"; }
[ -e res/slow/manifest.json ] || fail "the run after a pause wrote no manifest"
same_images

# The controller stopped past --slurm-max-outage: one error line says the job could not be cancelled and how
# to cancel it; nothing is recorded for the run.
rm -rf res
start_slow stopped.txt --slurm-max-outage 1
stop_slurmctld
if wait "$run"; then fail "vri-run succeeded although the controller was gone"; fi
errors=$(grep -c "^vri-run: error:" stopped.txt || true)
[ "$errors" -eq 1 ] || { cat stopped.txt; fail "$errors error lines, not one"; }
grep -q "^vri-run: error: squeue failed (.*; no answer for [0-9.]* s (--slurm-max-outage 1 s); could not cancel Slurm jobs [0-9,-]* ([0-9]* jobs\?) (.*): they may still run; cancel them with 'scancel [0-9 ]*' once the controller answers$" stopped.txt ||
    { cat stopped.txt; fail "the give-up line does not say that the jobs could not be cancelled"; }
[ ! -e res/slow/manifest.json ] || fail "a run that gave up wrote a manifest"
# Back again, the controller still knows the job; a rerun cancels it if it still runs and completes.
restart_slurmctld
[ -n "$(squeue --noheader --states=all --jobs="$job" --format=%i 2>/dev/null)" ] || fail "the restarted controller lost job $job"
"$bin/vri-run" --executor slurm --slurm-poll 0.2 --results res slow.yaml 2> rerun.txt || { cat rerun.txt; fail "the rerun failed"; }
same_images

# SIGTERM while squeue waits on a paused controller: vri-run stops and says it could not cancel its job.
rm -rf res
controller=$(cat cluster/slurmctld.pid)
start_slow terminated.txt
kill -STOP "$controller"
kill -TERM "$run"
if wait "$run"; then kill -CONT "$controller"; fail "vri-run exited 0 after SIGTERM"; fi
kill -CONT "$controller"
! grep -q "asking again" terminated.txt || { cat terminated.txt; fail "squeue stopped by the signal was taken for an outage"; }
grep -q "^vri-run: error: interrupted by SIGTERM; could not cancel Slurm jobs [0-9,-]* ([0-9]* jobs\?) (.*): they may still run; cancel them with 'scancel [0-9 ]*' once the controller answers$" terminated.txt ||
    { cat terminated.txt; fail "SIGTERM on a paused controller did not say the jobs could not be cancelled"; }
scancel "$job"
for _ in $(seq 300); do
    [ -z "$(squeue --noheader --states=PENDING,RUNNING,COMPLETING --format=%i)" ] && break
    sleep 0.2
done
[ -z "$(squeue --noheader --states=PENDING,RUNNING,COMPLETING --format=%i)" ] || { squeue; fail "jobs are left"; }

# The node fails under a job that Slurm requeues (its JobRequeue=1 default): the job pends under its id, a line
# says so at once, and it runs again once its old credential has expired (cred_expire, 20 s on the test
# cluster); the run completes with the local image, and the manifest names the requeue as an attempt before.
rm -rf res
start_slow requeued.txt
requeued_job=$job
scontrol update NodeName=vri-test-node State=DOWN Reason=vri-test
wait_for_line requeued.txt "^vri-run: slow: step '$slow_step': Slurm requeued job $requeued_job (restart 1): it runs again under its id, now [A-Z_]*"
wait "$run" || { cat requeued.txt; fail "the requeued run failed"; }
same_images
/usr/bin/python3 - "$slow_step" "job $requeued_job requeued by Slurm (restart 1)" <<'PY' || fail "the manifest does not name the requeue"
import json, sys
steps = {s["id"]: s for s in json.load(open("res/slow/manifest.json"))["steps"]}
sys.exit(0 if steps[sys.argv[1]]["execution"].get("earlier_attempts") == [sys.argv[2]] else 1)
PY

# The node cannot start a job (its prolog fails, once, for the slow render's job while break-launch exists):
# Slurm holds the job (squeue's reason: launch failed requeued held) and drains the node. vri-run takes that
# attempt as failed and cancels the job, which ends LAUNCH_FAILED: without retries one line names it; with
# --slurm-retries 1 it is submitted again and runs once the node is resumed. (Before JobRequeue=0 below: a
# job Slurm may not requeue is cancelled when its launch fails.)
cat > prolog.sh <<EOF
#!/bin/sh
[ -e "$PWD/break-launch" ] || exit 0
SLURM_CONF="$SLURM_CONF" scontrol show job "\$SLURM_JOB_ID" | grep -q "JobName=$slow_job\$" || exit 0
rm -f "$PWD/break-launch"
exit 1
EOF
chmod +x prolog.sh
echo "Prolog=$PWD/prolog.sh" >> cluster/slurm.conf
scontrol reconfigure
resume_node() { scontrol update NodeName=vri-test-node State=RESUME 2> /dev/null || true; }  # not drained: nothing to do
# slurmd drains its node when it tells the controller of the failed prolog, after the job's requeue.
wait_for_drain() {
    for _ in $(seq 300); do
        sinfo --noheader --Node --format=%T 2> /dev/null | grep -q '^drain' && return 0
        sleep 0.1
    done
    sinfo --Node --format='%N %T %E'
    fail "the failed launch did not drain the node"
}
# scontrol reconfigure reaches slurmd a moment later: until the prolog runs, the run succeeds and is repeated.
for attempt in $(seq 10); do
    rm -rf res
    touch break-launch
    status=0
    "$bin/vri-run" --executor slurm --slurm-poll 0.2 --slurm-bundle 0 --results res slow.yaml 2> launch.txt || status=$?
    [ -e break-launch ] || break
    [ "$attempt" -lt 10 ] || fail "slurmd never ran the prolog"
    sleep 1
done
[ "$status" -ne 0 ] || fail "vri-run succeeded although its job could not be started"
grep -q "^vri-run: slow: step '$slow_step': Slurm job [0-9]* could not be started on \(its node\|vri-test-node\) (squeue's reason: launch failed requeued held; sinfo -R says whether its node was drained for it); cancelling it$" launch.txt ||
    { cat launch.txt; fail "no line saying that the job could not be started and is cancelled"; }
grep -q "^vri-run: error: .*step '$slow_step' failed: Slurm job [0-9]* LAUNCH_FAILED\( on vri-test-node\)\? (launch failed requeued held, cancelled by vri-run); the job's output: " launch.txt ||
    { cat launch.txt; fail "no line naming the job its node could not start"; }
[ -z "$(squeue --noheader --states=PENDING,RUNNING,COMPLETING --format=%i)" ] || { squeue; fail "the held job is left"; }
# The node stays drained: the next run's node check pends; vri-run names squeue's reason and gives up after
# --slurm-max-pending, cancelling it. Held as well (scontrol hold, as an administrator would), the reason
# it gives up with says so (where the hold came after vri-run gave up, as on a loaded machine it may, the
# case runs again).
wait_for_drain
if "$bin/vri-run" --executor slurm --slurm-poll 0.2 --slurm-max-pending 3 --results res slow.yaml 2> drained.txt; then
    fail "vri-run succeeded on a drained node"
fi
grep -q "^vri-run: error: the Slurm check job [0-9]*: 1 job pending (squeue's reason: Nodes required for job are DOWN, DRAINED or reserved for jobs in higher priority partitions) for [0-9.]* s, none running: gave up after --slurm-max-pending 3 s; cancelled Slurm jobs [0-9]* (1 job)$" drained.txt ||
    { cat drained.txt; fail "no line naming the drained node's reason"; }
for attempt in 1 2 3; do
    "$bin/vri-run" --executor slurm --slurm-poll 0.2 --slurm-max-pending 10 --results res slow.yaml 2> held.txt &
    run=$!
    held_job=
    for _ in $(seq 300); do
        held_job=$(squeue --noheader --states=PENDING --name=vri:check --format=%i 2> /dev/null || true)
        [ -z "$held_job" ] || break
        sleep 0.1
    done
    [ -n "$held_job" ] || { cat held.txt; fail "vri-run's node check never pended"; }
    scontrol hold "$held_job" || true  # fails where vri-run has given up and cancelled it
    if wait "$run"; then fail "vri-run succeeded with its node check held"; fi
    run=
    grep -q "(squeue's reason: JobHeldAdmin)" held.txt && break
    [ "$attempt" -lt 3 ] || { cat held.txt; fail "vri-run gave up before each of three holds"; }
    echo "note: vri-run gave up before the hold reached its node check (attempt $attempt)"
done
grep -q "^vri-run: error: the Slurm check job $held_job: 1 job pending (squeue's reason: JobHeldAdmin) for [0-9.]* s, none running: gave up after --slurm-max-pending 10 s; cancelled Slurm jobs $held_job (1 job)$" held.txt ||
    { cat held.txt; fail "no line naming the held job's reason"; }
[ -z "$(squeue --noheader --states=PENDING,RUNNING,COMPLETING --format=%i)" ] || { squeue; fail "a job is left after giving up"; }
resume_node
rm -rf res
touch break-launch
"$bin/vri-run" --executor slurm --slurm-poll 0.2 --slurm-bundle 0 --slurm-retries 1 --results res slow.yaml 2> launch-retried.txt &
run=$!
wait_for_line launch-retried.txt "^vri-run: slow: step '$slow_step': Slurm job [0-9]* LAUNCH_FAILED\( on vri-test-node\)\?; retrying (attempt 2 of 2)$"
wait_for_drain
resume_node
wait "$run" || { cat launch-retried.txt; fail "the run retried after a failed launch failed"; }
run=
same_images

# The node fails under a job (scontrol sets it DOWN: Slurm kills the job's processes and ends it NODE_FAIL,
# requeueing off), and --slurm-retries 1 submits it again, which runs once the node is back (at once here:
# its slurmd answers, and ReturnToService=2 takes it back).
sed -i -e '/^Prolog=/d' -e 's/^ReturnToService=2$/ReturnToService=2\nJobRequeue=0/' cluster/slurm.conf
scontrol reconfigure
rm -rf res
start_slow retried.txt --slurm-retries 1
failed_job=$job
scontrol update NodeName=vri-test-node State=DOWN Reason=vri-test
wait_for_line retried.txt "^vri-run: slow: step '$slow_step': Slurm job $failed_job NODE_FAIL on vri-test-node; retrying (attempt 2 of 2)$"
wait "$run" || { cat retried.txt; fail "the retried run failed"; }
same_images
/usr/bin/python3 - "$slow_step" "job $failed_job NODE_FAIL on vri-test-node" <<'PY' || fail "the manifest does not name the attempt before"
import json, sys
steps = {s["id"]: s for s in json.load(open("res/slow/manifest.json"))["steps"]}
attempts = steps[sys.argv[1]]["execution"].get("earlier_attempts")
sys.exit(0 if attempts == [sys.argv[2]] else 1)
PY
# Without retries the same failure ends the run, one line naming the job and its state.
rm -rf res
start_slow failed.txt
scontrol update NodeName=vri-test-node State=DOWN Reason=vri-test
if wait "$run"; then fail "vri-run succeeded although its job failed with its node"; fi
grep -q "^vri-run: error: .*step '$slow_step' failed: Slurm job $job NODE_FAIL on vri-test-node (NodeDown)" failed.txt ||
    { cat failed.txt; fail "no line naming the job that failed with its node"; }

# Memory: a job over its --mem is killed by the cluster's enforcement (jobacct_gather's OverMemoryKill, which ends
# it FAILED (JobLaunchFailure), the cause only in its output). A site profile asks 16 MiB for a render, which the
# slow render's job exceeds (it holds some 80 MiB here): without retries one line names the job, OUT_OF_MEMORY
# and slurmstepd's words; with --slurm-retries 3 it is submitted again with --mem doubled until it fits (by
# 128 MiB), and the run completes with the local image, the manifest naming each attempt before.
printf 'kinds:\n  render: {mem: 16M}\n' > small-renders.yaml
rm -rf res
if VRI_SLURM_PROFILE=$PWD/small-renders.yaml "$bin/vri-run" --executor slurm --slurm-poll 0.2 --slurm-bundle 0 \
        --results res slow.yaml 2> oom.txt; then
    fail "vri-run succeeded although its render's job exceeded its memory"
fi
grep -q "^vri-run: error: .*step '$slow_step' failed: Slurm job [0-9]* OUT_OF_MEMORY on vri-test-node (slurmstepd: StepId=[0-9]*[.]batch exceeded memory limit ([0-9]* > 16777216)); the job's output: " oom.txt ||
    { cat oom.txt; fail "no line naming the job killed for its memory"; }
rm -rf res
VRI_SLURM_PROFILE=$PWD/small-renders.yaml "$bin/vri-run" --executor slurm --slurm-poll 0.2 --slurm-bundle 0 --slurm-retries 3 \
    --results res slow.yaml 2> oom-retried.txt || { cat oom-retried.txt; fail "the run retried for memory failed"; }
grep -q "^vri-run: slow: step '$slow_step': Slurm job [0-9]* OUT_OF_MEMORY on vri-test-node; retrying (attempt 2 of 4, --mem x2)$" oom-retried.txt ||
    { cat oom-retried.txt; fail "no line saying the job killed for its memory is retried with --mem doubled"; }
same_images
/usr/bin/python3 - "$slow_step" <<'PY' || fail "the manifest does not name the attempts killed for their memory"
import json, re, sys
steps = {s["id"]: s for s in json.load(open("res/slow/manifest.json"))["steps"]}
attempts = steps[sys.argv[1]]["execution"].get("earlier_attempts", [])
sys.exit(0 if attempts and all(re.fullmatch(r"job \d+ OUT_OF_MEMORY on vri-test-node", a) for a in attempts) else 1)
PY
echo "slurm_faults: OK"
