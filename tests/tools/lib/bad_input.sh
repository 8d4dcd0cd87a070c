# Sourced by the bad-input tests (tests/tools/bad_input_*.sh), after lib/scratch.sh.
#
#   bad CODE PATTERN -- COMMAND [ARGS...]
#
# runs COMMAND in the work directory ($VRI_SCRATCH/work, the current directory after sourcing) and
# checks the three things a user relies on when an input is bad:
#   - the exit code is CODE ("nonzero" accepts any non-zero code; a crash, 128 + signal, never passes);
#   - stderr is exactly one line and matches the extended regular expression PATTERN;
#   - the work directory is exactly as before: no file added (hidden temporary files included),
#     removed, replaced or written (its inode and ctime kept), and every FIFO, symlink or device in it
#     keeps its kind.
# Outputs go to $VRI_SCRATCH/logs, outside the work directory. bad_done prints the number of cases
# and fails when none ran.
#
# Each case runs under /usr/bin/time (GNU time, installed by scripts/install-deps.sh; the suite skips
# without it) and fails when its peak resident memory exceeds bad_max_rss_kb KiB: 256 MiB unless the
# suite sets another limit before its first case (issue 29: every allocation an input drives is bounded
# before it happens). bad_done prints the largest peak and its case.
[ -x /usr/bin/time ] || { echo "skip: GNU time (/usr/bin/time) missing for the peak resident memory"; exit 77; }
bad_max_rss_kb=$((256 * 1024))
# Under AddressSanitizer (make test-sanitize) the peak counts its shadow memory and the quarantine of
# freed blocks (256 MiB by default), not what vri allocates: measured and reported, not limited.
# grep reads all of ldd's lines: with -q it stops at the match, ldd dies of SIGPIPE and pipefail fails the test.
if ldd "$VRI_BIN/vri-render" 2> /dev/null | grep libasan > /dev/null; then bad_max_rss_kb=$((64 * 1024 * 1024)); fi
bad_rss_peak_kb=0
bad_rss_peak_case=none
bad_cases=0
bad_logs="$VRI_SCRATCH/logs"
mkdir -p "$bad_logs" "$VRI_SCRATCH/work"
cd "$VRI_SCRATCH/work"

# Every entry with its kind, size and mode, and a regular file's inode and status-change time: a write, a
# truncation, a replacement (a new inode) or a chmod changes them, and no program can set a ctime back. One
# find a snapshot, where hashing every file's content took two more processes and a third of each case's time.
# (It relies on the file system's fine timestamps: on one that keeps whole seconds, a same-size rewrite within
# the second of the file's creation would pass unseen.)
bad_snapshot() {
  find . -mindepth 1 \( -type f -printf '%p %y %s %m %i %C@\n' \) -o -printf '%p %y %s %m\n' | LC_ALL=C sort
}

bad() {
  local code=$1 pattern=$2
  shift 2
  [ "$1" = "--" ] && shift
  bad_cases=$((bad_cases + 1))
  local label="case $bad_cases ($*)"
  local before after rc=0
  before=$(bad_snapshot)
  /usr/bin/time -f %M -o "$bad_logs/rss" "$@" > "$bad_logs/out" 2> "$bad_logs/err" < /dev/null || rc=$?
  after=$(bad_snapshot)
  if [ "$code" = nonzero ]; then
    { [ "$rc" -ne 0 ] && [ "$rc" -lt 128 ]; } || fail "$label: exit $rc, expected a non-zero code below 128; stderr: $(head -c 500 "$bad_logs/err")"
  else
    [ "$rc" -eq "$code" ] || fail "$label: exit $rc, expected $code; stderr: $(head -c 500 "$bad_logs/err")"
  fi
  [ "$(wc -l < "$bad_logs/err")" -eq 1 ] ||
    fail "$label: expected one line on stderr, got $(wc -l < "$bad_logs/err"): $(head -c 500 "$bad_logs/err")"
  grep -Eq -- "$pattern" "$bad_logs/err" || fail "$label: stderr does not match /$pattern/: $(cat "$bad_logs/err")"
  [ "$before" = "$after" ] ||
    fail "$label: the work directory changed: $(diff <(echo "$before") <(echo "$after") | head -20)"
  # GNU time writes "Command exited with non-zero status N" before the number when the command fails.
  local rss
  rss=$(tail -n 1 "$bad_logs/rss")
  [ "$rss" -le "$bad_max_rss_kb" ] || fail "$label: peak resident memory $rss KiB, limit $bad_max_rss_kb KiB"
  if [ "$rss" -gt "$bad_rss_peak_kb" ]; then bad_rss_peak_kb=$rss bad_rss_peak_case=$label; fi
}

bad_done() {
  [ "$bad_cases" -gt 0 ] || fail "no bad-input case ran"
  echo "$bad_cases bad-input cases passed"
  echo "largest peak resident memory: $bad_rss_peak_kb KiB (limit $bad_max_rss_kb), $bad_rss_peak_case"
}
