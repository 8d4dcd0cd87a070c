#!/usr/bin/env bash
# How ctest runs a tool test (tests/CMakeLists.txt):
#     run_bounded.sh SECONDS SCRIPT
# SCRIPT runs in a process group of its own. Past SECONDS the group is listed (what still ran, for the
# failure's output), sent SIGTERM and, 20 s later, SIGKILL, and the test fails; when SCRIPT ends, whatever
# it left running in its group (a browser of a killed driver, a background job) is killed too. Either way
# nothing of the test outlives it holding ctest's output pipe, which would make ctest, and CI, wait for
# ever. Daemons that leave the group (a test cluster's, in sessions of their own) are the test's to stop.
# The exit status is SCRIPT's (77: skipped), or 1 past the limit.
set -u
limit=$1 script=$2
[[ $limit =~ ^[0-9]+$ ]] || { echo "FAIL: run_bounded.sh: SECONDS is a whole number, not '$limit'"; exit 1; }
marks=$(mktemp -d) || exit 1  # the timer leaves "fired" there
set -m  # each background job in a process group of its own, whose id is its pid
bash "$script" < /dev/null &
test_pid=$!
(
    sleep "$limit" &
    wait $!
    : > "$marks/fired"
    echo "FAIL: $(basename "$script") still runs after $limit s; its processes:"
    ps -o pid,etimes,stat,args -p "$(pgrep -d, -g "$test_pid")" 2>&1 | cut -c1-200
    kill -TERM -- "-$test_pid" 2>/dev/null
    sleep 20
    kill -KILL -- "-$test_pid" 2>/dev/null
) &
timer_pid=$!
# ctest stopped (Ctrl-C, or killed): the test's group, which no longer shares ctest's, stops with it.
trap 'kill -TERM -- "-$test_pid" "-$timer_pid" 2>/dev/null; rm -rf -- "$marks"; exit 130' INT TERM HUP
exec 2> /dev/null  # job control's own notes ("Terminated", "Killed") are not the test's output
wait "$test_pid"
status=$?
kill -KILL -- "-$timer_pid" "-$test_pid" 2>/dev/null
wait "$timer_pid" 2>/dev/null
[ ! -e "$marks/fired" ] || status=1
rm -rf -- "$marks"
exit "$status"
