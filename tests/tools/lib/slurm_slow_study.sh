# Sourced by the Slurm tests after scratch.sh: a study of one slow render and a diff that needs it, started on
# the test cluster in the background until the slow render's job runs.
#   write_slow_study RATE   tf.yaml and slow.yaml, the render at RATE samples per voxel; sets slow_step and
#                           slow_job (the step's Slurm job name)
#   start_slow LOG [OPTION...]   vri-run --executor slurm, a job per step, on slow.yaml into res in the
#                           background ($run), its stderr in LOG; waits until every job is submitted and the
#                           slow render's runs ($job)
#   interrupt_slow LOG COMMAND   start_slow LOG, then COMMAND (a function that interrupts the run: scancel of
#                           $job, a signal to $run), then waits for vri-run ($status, its exit status). Where
#                           the slow render ran to its end all the same (a loaded machine delayed the
#                           interruption past the render's seconds), its outputs are removed and the case
#                           runs again, three times at most.
#   clear_slow              removes the slow render's outputs, the diff's and the manifest from res
write_slow_study() {
    slow_step=riemann-entry-exit-corner-r$1
    slow_job=vri:slow:$slow_step
    cat > tf.yaml <<'YAML'
points:
  - [0.0, 0.0, 0.0, 0.0, 0.0]
  - [0.5, 0.9, 0.3, 0.1, 2.0]
  - [1.0, 0.2, 0.4, 1.0, 0.8]
YAML
    cat > slow.yaml <<YAML
name: slow
title: One slow render and a diff that needs it
paper: {paper: A, item: Fig. 4, says: a test}
scenes:
  cube: {field: linear, field_dims: [5, 5, 5], convention: node, tf: tf.yaml, size: [64, 48]}
methods:
  riemann: {placement: [entry-exit-corner], rate: [2, $1]}
comparisons:
  vs-fine: {reference: $slow_step}
YAML
}

start_slow() {
    local log=$1
    shift
    "$VRI_BIN/vri-run" --executor slurm --slurm-poll 0.2 --slurm-bundle 0 "$@" --results res slow.yaml 2> "$log" &
    run=$!
    job=
    for _ in $(seq 600); do
        job=$(squeue --noheader --states=RUNNING --name="$slow_job" --format=%i 2>/dev/null || true)
        [ -n "$job" ] && grep -q "steps in Slurm jobs" "$log" && return 0
        sleep 0.1
    done
    kill "$run"
    cat "$log"
    fail "the slow render's job never ran"
}

clear_slow() { rm -f res/slow/"$slow_step".* res/slow/vs-fine-* res/slow/manifest.json; }

interrupt_slow() {
    local log=$1 command=$2 attempt
    for attempt in 1 2 3; do
        start_slow "$log"
        "$command" || true
        status=0
        wait "$run" || status=$?
        # Its output there, or the line saying it ran, whichever vri-run got to before it stopped.
        ! ls res/slow/"$slow_step".* > /dev/null 2>&1 && ! grep -q "ran vri-render $slow_step (" "$log" && return 0
        echo "note: the slow render ran to its end before '$command' reached it (attempt $attempt)"
        clear_slow
    done
    cat "$log"
    fail "the slow render ran to its end before each of three '$command' reached it"
}
