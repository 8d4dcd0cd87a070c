#!/usr/bin/env bash
# Signals and temporary files (issue 29, item 12). A SIGTERM or SIGINT to a tool while a temporary file
# exists removes it on the way out, and the tool still dies of the signal; only kill -9 leaves one, and
# the next run that writes the same output removes it (its process is gone) while a user's look-alike
# files stay. Deterministic first: vri-convert writes a header and its raw file together, staging the 16 MiB raw
# beside its target before it opens the header, here a FIFO that nobody reads, so it blocks there with
# the temporary file in place until the signal comes.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
source "$(dirname "${BASH_SOURCE[0]}")/lib/blob.sh"
bin=${VRI_BIN:?}

write_blob_scene
head -c $((256 * 256 * 256)) /dev/urandom > big_256x256x256_uint8.raw

# blocked_convert: starts vri-convert into the FIFO out.nhdr, in the background with SIGINT at its
# default action (a non-interactive shell's background jobs ignore it, and vri keeps what it inherits),
# and waits for its temporary raw file; sets pid and tmp.
blocked_convert() {
  rm -f out.nhdr
  mkfifo out.nhdr
  env --default-signal=INT "$bin/vri-convert" -q big_256x256x256_uint8.raw out.nhdr &
  pid=$!
  tmp=".out.tmp.$pid.raw"
  for _ in $(seq 600); do [ -e "$tmp" ] && break; sleep 0.05; done
  [ -e "$tmp" ] || fail "vri-convert made no temporary file $tmp within 30 s"
}

for signal in TERM INT; do
  blocked_convert
  kill -s "$signal" "$pid"
  rc=0; wait "$pid" || rc=$?
  [ "$rc" -eq $((128 + $(kill -l "$signal"))) ] || fail "SIG$signal: exit $rc, expected death by the signal"
  [ ! -e "$tmp" ] || fail "SIG$signal left $tmp ($(stat -c %s "$tmp") bytes)"
  [ -z "$(find . -name '.*.tmp.*')" ] || fail "SIG$signal left $(find . -name '.*.tmp.*')"
  [ -p out.nhdr ] && [ ! -e out.raw ] || fail "SIG$signal: the outputs changed: $(ls -l out.*)"
done

# vri-render, signalled while it writes a 3000x3000 image (tens of MB, so the temporary file exists for a
# while): polled without sleeping, the signal lands with the file in place; a try where the write was
# over first proves nothing and is repeated.
for signal in TERM INT; do
  landed=0
  for _ in 1 2 3 4 5; do
    env --default-signal=INT "$bin/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 3000x3000 -q \
        -o big.exr &
    pid=$!
    while [ ! -e ".big.tmp.$pid.exr" ] && kill -0 "$pid" 2> /dev/null; do :; done
    seen=0; [ -e ".big.tmp.$pid.exr" ] && seen=1
    kill -s "$signal" "$pid" 2> /dev/null || true
    rc=0; wait "$pid" || rc=$?
    [ -z "$(find . -name '.*.tmp.*')" ] || fail "vri-render: SIG$signal left $(find . -name '.*.tmp.*')"
    rm -f big.exr
    if [ "$seen" -eq 1 ] && [ "$rc" -eq $((128 + $(kill -l "$signal"))) ]; then landed=1; break; fi
  done
  [ "$landed" -eq 1 ] || fail "vri-render: no SIG$signal landed while its temporary file existed in 5 tries"
done

# kill -9 leaves the file; the next vri-convert writing out.nhdr removes it, keeping the look-alikes.
blocked_convert
kill -s KILL "$pid"
wait "$pid" 2> /dev/null || true  # bash reports the kill
[ -e "$tmp" ] || fail "kill -9 should leave $tmp (nothing runs in a killed process)"
dead=$pid
touch ".out.tmp.$dead.raw.bak" ".out.tmp.$dead.nhdr.old" ".notes.tmp.$dead.raw" ".out.tmp.0$dead.raw" "sub.out.tmp.$dead.raw"
touch ".out.tmp.$$.raw"  # this shell's: a live writer's
rm out.nhdr
"$bin/vri-convert" -q big_256x256x256_uint8.raw out.nhdr || fail "the conversion after kill -9 failed"
[ ! -e "$tmp" ] || fail "the next run kept the dead writer's $tmp"
for kept in ".out.tmp.$dead.raw.bak" ".out.tmp.$dead.nhdr.old" ".notes.tmp.$dead.raw" ".out.tmp.0$dead.raw" \
            "sub.out.tmp.$dead.raw" ".out.tmp.$$.raw"; do
  [ -e "$kept" ] || fail "$kept was removed: not a temporary file of a process that is gone"
done
cmp -s out.raw big_256x256x256_uint8.raw || fail "out.raw is not the volume"

# vri-render does the same for its image: a dead writer's temporary file of out.exr goes, look-alikes stay.
dead=4194000
while kill -0 "$dead" 2> /dev/null; do dead=$((dead + 1)); done
touch ".out.tmp.$dead.exr" ".out.tmp.$dead.exr.bak" ".out.tmp.$dead.png" ".notes.tmp.$dead.txt" ".out.tmp.$$.exr"
"$bin/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 8x8 -q -o out.exr
[ ! -e ".out.tmp.$dead.exr" ] || fail "vri-render kept a dead writer's temporary file of its output"
for kept in ".out.tmp.$dead.exr.bak" ".out.tmp.$dead.png" ".notes.tmp.$dead.txt" ".out.tmp.$$.exr"; do
  [ -e "$kept" ] || fail "vri-render removed $kept"
done
echo "signals: all checks passed"
