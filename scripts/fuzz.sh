#!/usr/bin/env bash
# make fuzz: runs each libFuzzer target of tests/fuzz for FUZZ_SECONDS, seeded with its committed corpus
# (tests/fuzz/corpus/NAME, read only) and dictionary; what it learns goes to BUILD/corpus/NAME, a crashing
# input to BUILD/findings/NAME-crash-*. Prints each target's executions; fails if any target found something.
#   scripts/fuzz.sh BUILD SECONDS NAME...
set -euo pipefail
build=$1 seconds=$2
shift 2
source=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$build/findings"
status=0
summary=()
for name in "$@"; do
    mkdir -p "$build/corpus/$name"
    log="$build/findings/$name.log"
    rc=0
    "$build/tests/fuzz/vri-fuzz-$name" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=4096 \
        -print_final_stats=1 -dict="$source/tests/fuzz/dict/$name.dict" \
        -artifact_prefix="$build/findings/$name-" "$build/corpus/$name" "$source/tests/fuzz/corpus/$name" \
        > "$log" 2>&1 || rc=$?
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
    if [ "$rc" -ne 0 ]; then
        status=1
        summary+=("$name: FOUND a failure after ${runs:-?} executions (exit $rc), see $log")
    else
        summary+=("$name: ${runs:-?} executions in ${seconds} s, nothing found")
    fi
done
printf 'fuzz: %s\n' "${summary[@]}"
exit $status
