# Sourced by the Slurm tests: a real single-node Slurm cluster from Debian's slurm-wlm and munge, all of
# it in $1 (configuration, key, state, logs), on loopback ports of its own (below the range the kernel
# gives outgoing connections, and chosen again where another cluster took them first); SLURM_CONF points the
# client commands at it. Nothing of the machine's own Slurm or munge is read or touched. The daemons' Unix
# sockets (munged's, and each job step's, which Slurm names <spool>/<node>_<job>.<step>) live in a private
# folder under /tmp, removed at exit: a socket's path holds at most 107 bytes, which a scratch folder in a
# clone a few levels deep passes (slurmd then cannot start the job: "launch failed requeued held"). The
# daemons are stopped by the pids they wrote when the test exits. One setting departs from Slurm's defaults:
# batch_sched_delay=0 starts a job as soon as the node is free instead of up to 3 s later, which halves
# the time a test of many short jobs waits (6 two-CPU jobs on two CPUs: 18 s -> 8 s); cred_expire=20 (of 120)
# holds a requeued job back 21 s instead of 121 (Slurm keeps it from starting until its old credential has
# expired, and one started sooner fails with "Job credential revoked"). Memory is enforced as
# a site without cgroups enforces it: jobacct_gather/linux reads each job's resident memory every second and
# kills a job over its --mem (OverMemoryKill), which Slurm then ends FAILED with the cause in its output.
#   start_slurm_cluster DIR [MESSAGE_TIMEOUT] [NODES]   exits 77 (skip) with one line when the daemons cannot
#       start here; MESSAGE_TIMEOUT (seconds, Slurm's 10 by default) bounds how long a client waits for the
#       controller; NODES 1 (vri-test-node, every core of this machine) or 2 (vri-test-node1 and 2, two slurmd
#       on ports of their own, the cores and memory shared between them)
#   stop_slurmctld / restart_slurmctld   the controller stopped (by its pid) and started again on its saved state
# A watchdog bounds the whole test: one still running VRI_SLURM_TEST_LIMIT seconds (600 unless set) after its
# cluster started prints what the cluster holds (squeue, sinfo, the daemons' last log lines) and stops the
# test's own processes with SIGTERM (vri-run then cancels its jobs), so that a job the cluster never starts
# fails the test with what it waited for instead of holding ctest, and CI, for ever.

slurm_daemon_pids=()
slurm_watchdog_pid=
slurm_sockets=

stop_slurm_cluster() {
    local pid
    [ -z "$slurm_watchdog_pid" ] || kill "$slurm_watchdog_pid" 2>/dev/null || true
    slurm_watchdog_pid=
    trap - TERM
    for pid in "${slurm_daemon_pids[@]}"; do kill "$pid" 2>/dev/null || true; done
    for pid in "${slurm_daemon_pids[@]}"; do
        for _ in $(seq 100); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
        kill -9 "$pid" 2>/dev/null || true
    done
    slurm_daemon_pids=()
    # A job still running when its slurmd stopped leaves its slurmstepd (a daemon of its own) and the job's
    # processes under it: those of this cluster, and only those, are known by the SLURM_CONF in the
    # slurmstepd's environment.
    if [ -n "${slurm_dir:-}" ]; then
        for pid in $(pgrep -x slurmstepd); do
            { tr '\0' '\n' < "/proc/$pid/environ"; } 2>/dev/null | grep -qxF "SLURM_CONF=$slurm_dir/slurm.conf" &&
                kill_slurm_tree "$pid"
        done
    fi
    [ -z "$slurm_sockets" ] || rm -rf "$slurm_sockets"
    slurm_sockets=
    return 0
}

# PID and every process under it, children first stopped (SIGSTOP) so that none escapes while the tree is
# walked, then all killed.
kill_slurm_tree() {
    local child
    kill -STOP "$1" 2>/dev/null || return 0
    for child in $(pgrep -P "$1"); do kill_slurm_tree "$child"; done
    kill -9 "$1" 2>/dev/null || true
}

# The pid a daemon wrote to FILE, waited for up to 10 s, added to those stopped at exit.
slurm_daemon_pid() {
    local file=$1 what=$2
    for _ in $(seq 100); do [ -s "$file" ] && break; sleep 0.1; done
    [ -s "$file" ] || { echo "SKIP: $what did not start (see $(dirname "$file")/log)"; exit 77; }
    slurm_daemon_pids+=("$(cat "$file")")
}

start_slurm_cluster() {
    local dir=$1 message_timeout=${2:-10} nodes=${3:-1} program
    for program in munged slurmctld slurmd sbatch squeue scancel; do
        command -v "$program" > /dev/null || { echo "SKIP: $program is not installed (make deps installs slurm-wlm and munge)"; exit 77; }
    done
    [ "$(id -u)" -eq 0 ] || { echo "SKIP: slurmd runs jobs as their users and needs root to start"; exit 77; }
    trap stop_slurm_cluster EXIT
    slurm_sockets=$(mktemp -d /tmp/vri-slurm.XXXXXX) || { echo "FAIL: no private folder for the cluster's sockets in /tmp"; exit 1; }
    local longest="$slurm_sockets/spool/vri-test-node2/vri-test-node2_67043328.4294967292"
    [ "${#longest}" -le 107 ] || { echo "FAIL: the cluster's socket paths would pass 107 bytes ($longest)"; exit 1; }
    mkdir -p "$dir/munge" "$dir/log"
    chmod 700 "$dir/munge"
    head -c 1024 /dev/urandom > "$dir/munge/munge.key"
    chmod 400 "$dir/munge/munge.key"
    munged --force --key-file="$dir/munge/munge.key" --socket="$slurm_sockets/munge" --pid-file="$dir/munge/munged.pid" \
        --log-file="$dir/log/munged.log" --seed-file="$dir/munge/seed" \
        || { echo "SKIP: munged cannot start here (see $dir/log/munged.log)"; exit 77; }
    slurm_daemon_pid "$dir/munge/munged.pid" munged

    [ "$nodes" = 1 ] || [ "$nodes" = 2 ] || { echo "FAIL: start_slurm_cluster: NODES is 1 or 2, not $nodes"; exit 1; }
    local memory=$(( ($(awk '/^MemTotal:/ {print $2}' /proc/meminfo) / 1024 - 512) / nodes ))
    local cpus=$(( $(nproc) / nodes ))
    [ "$cpus" -ge 1 ] || { echo "SKIP: $nodes nodes need $nodes cores"; exit 77; }
    export SLURM_CONF=$dir/slurm.conf
    slurm_dir=$dir
    # A daemon that cannot bind its port (another cluster starting beside this one took it between the look
    # and the bind) stops at once: the cluster starts again on other ports, three times at most.
    local attempt log
    for attempt in 1 2 3; do
        start_slurm_daemons "$dir" "$message_timeout" "$nodes" "$cpus" "$memory" && break
        grep -qs "Address already in use" "$dir"/log/*.log ||
            { echo "SKIP: the test cluster did not come up (see $dir/log)"; exit 77; }
        [ "$attempt" -lt 3 ] || { echo "FAIL: the test cluster found its ports taken three times (see $dir/log)"; exit 1; }
        stop_slurm_daemons
        rm -rf "$dir/state" "$slurm_sockets/spool"
        for log in "$dir"/log/slurm*; do mv "$log" "$log.attempt-$attempt"; done
    done
    start_slurm_watchdog
}

# Three ports a cluster takes (the controller's, then a slurmd's each) that no socket of this machine holds,
# listening, connected or closing, below the kernel's range for outgoing connections (ip_local_port_range),
# from which any client could otherwise take one while the cluster starts.
pick_slurm_port() {
    local low=32768 range port base=20000
    range=$(cat /proc/sys/net/ipv4/ip_local_port_range 2> /dev/null) && low=${range%%[[:space:]]*}
    if [ "$low" -le 10400 ]; then low=30000; elif [ "$low" -le 20400 ]; then base=10000; fi  # no room below: retries
    port=$(( base + (RANDOM % ((low - base) / 4 - 1)) * 4 ))
    while ss -Htan 2> /dev/null | awk '{print $4}' | grep -qE ":($port|$((port + 1))|$((port + 2)))$"; do
        port=$((port + 4))
    done
    echo "$port"
}

# The controller and the slurmds of DIR's cluster on fresh ports, and a wait (at most a minute) until every
# node is idle; false when a daemon stopped meanwhile.
start_slurm_daemons() {
    local dir=$1 message_timeout=$2 nodes=$3 cpus=$4 memory=$5 port names=() k
    port=$(pick_slurm_port)
    if [ "$nodes" = 1 ]; then names=(vri-test-node); else names=(vri-test-node1 vri-test-node2); fi
    local spool=$slurm_sockets/spool
    mkdir -p "$dir/state" "$spool"
    cat > "$dir/slurm.conf" <<EOF
ClusterName=vritest
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$slurm_sockets/munge,cred_expire=20
CredType=cred/munge
StateSaveLocation=$dir/state
SlurmdSpoolDir=$spool/%n
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd-%n.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd-%n.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/linux
JobAcctGatherFrequency=task=1
JobAcctGatherParams=OverMemoryKill
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
MpiDefault=none
MessageTimeout=$message_timeout
ReturnToService=2
MinJobAge=3600
SchedulerParameters=batch_sched_delay=0
PropagateResourceLimits=NONE
EOF
    for k in "${!names[@]}"; do
        echo "NodeName=${names[k]} NodeAddr=127.0.0.1 NodeHostname=${names[k]} Port=$((port + 1 + k)) CPUs=$cpus RealMemory=$memory State=UNKNOWN" >> "$dir/slurm.conf"
        mkdir -p "$spool/${names[k]}"
    done
    echo "PartitionName=test Nodes=ALL Default=YES MaxTime=INFINITE State=UP" >> "$dir/slurm.conf"
    slurmctld -i >> "$dir/log/slurmctld.out" 2>&1 || return 1
    slurm_daemon_pid "$dir/slurmctld.pid" slurmctld
    for k in "${!names[@]}"; do
        slurmd -N "${names[k]}" >> "$dir/log/slurmd-${names[k]}.out" 2>&1 || return 1
        slurm_daemon_pid "$dir/slurmd-${names[k]}.pid" slurmd
    done
    local deadline=$((SECONDS + 60)) pid
    while [ "$SECONDS" -lt "$deadline" ]; do
        for pid in "${slurm_daemon_pids[@]:1}"; do kill -0 "$pid" 2> /dev/null || return 1; done
        [ "$(timeout 10 sinfo --noheader --Node --format=%T 2>/dev/null | sort -u)" = idle ] &&
            [ "$(timeout 10 sinfo --noheader --Node --format=%N 2>/dev/null | wc -l)" = "$nodes" ] && return 0
        sleep 0.2
    done
    return 1
}

# The slurmctld and slurmds started (every daemon but munged, the first), stopped and forgotten.
stop_slurm_daemons() {
    local pid
    for pid in "${slurm_daemon_pids[@]:1}"; do kill "$pid" 2> /dev/null || true; done
    for pid in "${slurm_daemon_pids[@]:1}"; do
        for _ in $(seq 100); do kill -0 "$pid" 2> /dev/null || break; sleep 0.1; done
        kill -9 "$pid" 2> /dev/null || true
    done
    slurm_daemon_pids=("${slurm_daemon_pids[0]}")
    rm -f "$slurm_dir"/slurmctld.pid "$slurm_dir"/slurmd-*.pid
}

# The watchdog (above). It sleeps in the background so that SIGTERM from stop_slurm_cluster ends it at once,
# its sleep included, and leaves nothing holding ctest's pipe; the test's own TERM trap makes it exit 1, which
# runs its EXIT trap (the daemons stopped).
start_slurm_watchdog() {
    local limit=${VRI_SLURM_TEST_LIMIT:-600} test_pid=$$
    [[ $limit =~ ^[0-9]+$ ]] || { echo "FAIL: VRI_SLURM_TEST_LIMIT is a whole number of seconds, not '$limit'"; exit 1; }
    trap "echo 'FAIL: stopped by the Slurm test watchdog after $limit s'; exit 1" TERM
    (
        set +eu +o pipefail  # the test's strict mode: a failing look below must not end the watchdog
        watchdog=$BASHPID
        trap 'kill "$nap" 2>/dev/null; exit 0' TERM
        sleep "$limit" &
        nap=$!
        wait "$nap"
        echo "FAIL: the test still runs $limit s after its Slurm cluster started (VRI_SLURM_TEST_LIMIT); the cluster holds:"
        timeout 10 squeue --states=all --format='%i %j %T %r %S %M %N' 2>&1
        timeout 10 sinfo --Node --format='%N %T %E' 2>&1
        tail -n 20 "$slurm_dir/log/slurmctld.log"
        local log
        for log in "$slurm_dir"/log/slurmd-*.log; do echo "$log:"; tail -n 20 "$log"; done
        trap - TERM
        kill -TERM $(pgrep -P "$test_pid" | grep -vx "$watchdog") 2>/dev/null
        kill -TERM "$test_pid"
    ) &
    slurm_watchdog_pid=$!
}

# The controller's pid, stopped with SIGTERM and waited for; it is no longer stopped at exit.
stop_slurmctld() {
    local pid k
    pid=$(cat "$slurm_dir/slurmctld.pid")
    kill "$pid"
    for _ in $(seq 100); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    ! kill -0 "$pid" 2>/dev/null || { echo "FAIL: slurmctld $pid did not stop"; exit 1; }
    for k in "${!slurm_daemon_pids[@]}"; do [ "${slurm_daemon_pids[$k]}" = "$pid" ] && unset 'slurm_daemon_pids[k]'; done
    rm -f "$slurm_dir/slurmctld.pid"
}

# The controller started again on its saved state (its jobs kept), waited for until squeue answers.
restart_slurmctld() {
    slurmctld -i >> "$slurm_dir/log/slurmctld.out" 2>&1 || { echo "FAIL: slurmctld did not start again (see $slurm_dir/log)"; exit 1; }
    slurm_daemon_pid "$slurm_dir/slurmctld.pid" slurmctld
    for _ in $(seq 150); do squeue > /dev/null 2>&1 && return 0; sleep 0.2; done
    echo "FAIL: the restarted slurmctld does not answer (see $slurm_dir/log)"
    exit 1
}
