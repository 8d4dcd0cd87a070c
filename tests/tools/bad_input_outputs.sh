#!/usr/bin/env bash
# Outputs that never damage the machine and never lie (issue 13, items 1 and 3): a full disk or a file
# size limit is one line and a non-zero exit with no file and no temporary file left; an output path
# that is a directory, socket or link loop is refused; a device, FIFO or symlink given as an output
# keeps its kind. Runs unprivileged; the cases that need a private device node (mknod) or a tiny tmpfs
# (a real ENOSPC) run only as root and say so when skipped.
# A tmpfs left mounted by a killed run would make lib/scratch.sh's rm -rf fail.
[ -n "${VRI_SCRATCH:-}" ] && mountpoint -q "$VRI_SCRATCH/tiny" 2> /dev/null && umount "$VRI_SCRATCH/tiny"
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
source "$(dirname "${BASH_SOURCE[0]}")/lib/blob.sh"
source "$(dirname "${BASH_SOURCE[0]}")/lib/bad_input.sh"
bin=$VRI_BIN

# Inputs, in the work directory (each case checks that it is left exactly as it was).
write_blob_scene
head -c 32768 /dev/urandom > noise_32x32x32_uint8.raw   # noise: no format compresses it below 32 KB
# Helpers are arrays, not functions: each case runs under GNU time (lib/bad_input.sh), which runs programs.
render=("$bin/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 64x64 -q)
"${render[@]}" --step 0.5 -o a.exr
"${render[@]}" --step 0.25 -o b.exr
mkdir taken.exr

# limited KB COMMAND...: COMMAND under a file size limit of KB kilobytes (ulimit -f, RLIMIT_FSIZE). A write
# past it fails with EFBIG; the tools ignore SIGXFSZ themselves, so the test does not trap it. The limit
# holds for the harness's stderr log too, so it is at least 1 KB and every output under test is larger.
limited=(bash -c 'ulimit -f "$0" && exec "$@"')

# A FIFO with a reader that discards what it gets, for an output that is not the one under test.
mkfifo stream.exr
# (': <> stream.exr' releases the reader if the command never opened the FIFO.)
drained=(bash -c 'cat stream.exr > /dev/null & reader=$!; rc=0; "$@" || rc=$?; : <> stream.exr; wait "$reader"; exit "$rc"' drained)

# A full disk, as a file size limit: every output kind of every tool that writes files.
efbig="cannot write: File too large$"
bad 1 "^vri-render: error: out\.exr: $efbig" -- "${limited[@]}" 8 "$bin/vri-render" --volume blob_8x8x8_uint8.raw \
    --tf tf.yaml --size 64x64 --step 0.5 -q -o out.exr
bad 1 "^vri-render: error: out\.png: $efbig" -- "${drained[@]}" "${limited[@]}" 1 "$bin/vri-render" --volume blob_8x8x8_uint8.raw \
    --tf tf.yaml --size 64x64 --step 0.5 -q -o stream.exr --png out.png
bad 1 "^vri-render: error: out\.json: $efbig" -- "${drained[@]}" "${limited[@]}" 1 "$bin/vri-render" \
    --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 64x64 --step 0.5 -q -o stream.exr --stats out.json
bad 1 "^vri-render: error: ray\.csv: $efbig" -- "${drained[@]}" "${limited[@]}" 1 "$bin/vri-render" \
    --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 64x64 --method coupled --log-ray 32,32 --log ray.csv -q \
    -o stream.exr
bad 1 "^vri-reference: error: out\.exr: $efbig" -- "${limited[@]}" 1 "$bin/vri-reference" --volume blob_8x8x8_uint8.raw \
    --tf tf.yaml --size 16x16 -q -o out.exr
for ext in vdb raw; do
  bad 1 "^vri-convert: error: out\.$ext: $efbig" -- "${limited[@]}" 8 "$bin/vri-convert" noise_32x32x32_uint8.raw out.$ext
done
for ext in nhdr dat; do   # the raw file beside the header is the large one
  bad 1 "^vri-convert: error: out\.raw: $efbig" -- "${limited[@]}" 8 "$bin/vri-convert" noise_32x32x32_uint8.raw out.$ext
done
bad 1 "^vri-tf: error: out\.csv: $efbig" -- "${limited[@]}" 8 "$bin/vri-tf" tf.yaml -o out.csv
bad 1 "^vri-diff: error: out\.json: $efbig" -- "${limited[@]}" 1 "$bin/vri-diff" a.exr a.exr --json out.json
bad 1 "^vri-diff: error: out\.csv: $efbig" -- "${limited[@]}" 1 "$bin/vri-diff" a.exr a.exr --histogram out.csv
bad 1 "^vri-diff: error: out\.exr: $efbig" -- "${limited[@]}" 1 "$bin/vri-diff" a.exr b.exr --diff-image out.exr
bad 1 "^vri-rays2d: error: out\.csv: $efbig" -- "${limited[@]}" 1 "$bin/vri-rays2d" --placements entry --rates 2 -o out.csv
"$bin/vri-diff" a.exr a.exr --json d.json > /dev/null
rows=()
for i in $(seq 30); do rows+=(--row "row $i" d.json); done
bad 1 "^vri-tabulate: error: out\.md: $efbig" -- "${limited[@]}" 1 "$bin/vri-tabulate" --layout thresholds "${rows[@]}" \
    -o out.md
# A command's outputs go out together: one that fails leaves every other as it was (a.exr and old.csv are
# not replaced by this run's, and no .png appears).
bad 1 "^vri-render: error: out\.json: $efbig" -- "${limited[@]}" 2 "$bin/vri-render" --volume blob_8x8x8_uint8.raw \
    --tf tf.yaml --size 8x8 -q -o a.exr --png new.png --stats out.json
echo "an earlier table" > old.csv
bad 1 "^vri-tabulate: error: out\.md: $efbig" -- "${limited[@]}" 2 "$bin/vri-tabulate" --layout thresholds "${rows[@]}" \
    --csv old.csv -o out.md
rm d.json old.csv

# Outputs that are neither a file, a device, a FIFO nor '-': refused, and left as they are.
bad 1 "^vri-render: error: -o: taken\.exr: cannot write: it is a directory; expected a regular file" -- "${render[@]}" -o taken.exr
# Every output is checked before the render: a bad one leaves the others unwritten (a.exr as it was).
bad 1 "^vri-render: error: --stats: taken\.exr: cannot write: it is a directory" -- "${render[@]}" -o a.exr --stats taken.exr
bad 1 "^vri-reference: error: --png: taken\.exr: cannot write: it is a directory" -- "$bin/vri-reference" \
    --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 8x8 -q -o a.exr --png taken.exr
# Two dangling links to one target are one output: the second write would replace the first.
ln -s target.exr link1.exr && ln -s target.exr link2.exr
bad 64 "^vri-reference: error: --error-image: 'link2\.exr' is also -o's output" -- "$bin/vri-reference" \
    --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 8x8 -q -o link1.exr --error-image link2.exr
rm link1.exr link2.exr
bad 1 "^vri-tf: error: taken\.exr: cannot write: it is a directory" -- "$bin/vri-tf" tf.yaml -o taken.exr
mkdir taken.nhdr   # the header cannot be written: its raw file is not written either
bad 1 "^vri-convert: error: taken\.nhdr: cannot write: it is a directory" -- "$bin/vri-convert" noise_32x32x32_uint8.raw \
    taken.nhdr
rmdir taken.nhdr
ln -s loop.csv loop.csv
bad 1 "^vri-tf: error: loop\.csv: cannot write: Too many levels of symbolic links$" -- "$bin/vri-tf" tf.yaml -o loop.csv
rm loop.csv
if command -v python3 > /dev/null; then
  /usr/bin/python3 -c 'import socket, sys; socket.socket(socket.AF_UNIX).bind(sys.argv[1])' out.sock
  bad 1 "^vri-tf: error: out\.sock: cannot write: it is a socket" -- "$bin/vri-tf" tf.yaml -o out.sock
  rm out.sock
else
  echo "python3 not installed: the socket case is skipped"
fi

# A private device node as root: /dev/full's numbers make every write fail with ENOSPC.
if [ "$(id -u)" -eq 0 ] && mknod full c 1 7 2> /dev/null; then
  enospc="cannot write: No space left on device$"
  ln -s full full.exr && ln -s full full.vdb   # a link to a device: written through, and it stays a link
  bad 1 "^vri-tf: error: full: $enospc" -- "$bin/vri-tf" tf.yaml -o full
  bad 1 "^vri-render: error: full\.exr: $enospc" -- "${render[@]}" -o full.exr
  bad 1 "^vri-convert: error: full\.vdb: $enospc" -- "$bin/vri-convert" noise_32x32x32_uint8.raw full.vdb
  to_full=(bash -c '"$@" > full' to_full)
  bad 1 "^vri-tf: error: -: $enospc" -- "${to_full[@]}" "$bin/vri-tf" tf.yaml -o -
  bad 1 "^vri-convert: error: stdout: cannot write what was printed" -- "${to_full[@]}" "$bin/vri-convert" --info --json \
      noise_32x32x32_uint8.raw
  [ -L full.exr ] && [ -L full.vdb ] || fail "a link to the device is no longer a link"
  rm full.exr full.vdb
  [ -c full ] || fail "the device node is no longer a character device"
  rm full
else
  echo "not root (or mknod not allowed): the private /dev/full cases are skipped"
fi

# A real full disk as root: a 16 KB tmpfs beside the work directory.
tiny=$VRI_SCRATCH/tiny
mkdir -p "$tiny"
if [ "$(id -u)" -eq 0 ] && mount -t tmpfs -o size=16k tmpfs "$tiny" 2> /dev/null; then
  trap 'umount "$tiny"' EXIT
  enospc="cannot write: No space left on device$"
  bad 1 "^vri-convert: error: $tiny/out\.vdb: $enospc" -- "$bin/vri-convert" noise_32x32x32_uint8.raw "$tiny/out.vdb"
  bad 1 "^vri-render: error: $tiny/out\.exr: $enospc" -- "${render[@]}" -o "$tiny/out.exr"
  [ -z "$(ls -A "$tiny")" ] || fail "the full tmpfs holds $(ls -A "$tiny")"
else
  echo "not root (or mount not allowed): the tmpfs ENOSPC cases are skipped"
fi

# And the kinds that are written: outside the harness, each checked by hand.
cd "$VRI_SCRATCH" && mkdir good && cd good
"$bin/vri-tf" ../work/tf.yaml -o tf.csv
mkfifo tf.fifo
cat tf.fifo > tf-from-fifo.csv &
"$bin/vri-tf" ../work/tf.yaml -o tf.fifo
wait $!
cmp -s tf.csv tf-from-fifo.csv || fail "vri-tf through a FIFO wrote other bytes"
[ -p tf.fifo ] || fail "the FIFO is no longer a FIFO"
ln -s /proc/self/fd/1 stdout.csv   # as /dev/stdout is: the tool's own stdout, a pipe here
"$bin/vri-tf" ../work/tf.yaml -o stdout.csv | cat > tf-from-stdout.csv
cmp -s tf.csv tf-from-stdout.csv && [ -L stdout.csv ] || fail "vri-tf through a link to its stdout"
rm stdout.csv
ln -s made/real.exr link.exr   # dangling: its target is created, and it stays a link
"$bin/vri-render" --volume ../work/blob_8x8x8_uint8.raw --tf ../work/tf.yaml --size 64x64 --step 0.5 -q -o link.exr
[ -L link.exr ] && "$bin/vri-diff" made/real.exr ../work/a.exr --fail 0 > /dev/null ||
  fail "vri-render through a dangling link"
expected="link.exr made tf-from-fifo.csv tf-from-stdout.csv tf.csv tf.fifo"
if [ "$(id -u)" -eq 0 ] && mknod null c 1 3 2> /dev/null; then
  expected="link.exr made null null.vdb tf-from-fifo.csv tf-from-stdout.csv tf.csv tf.fifo"
  ln -s null null.vdb
  "$bin/vri-convert" ../work/noise_32x32x32_uint8.raw null.vdb -q
  [ -c null ] && [ -L null.vdb ] || fail "vri-convert replaced a link to a device"
fi
[ "$(ls -A | LC_ALL=C sort | tr '\n' ' ')" = "$expected " ] || fail "files left behind: $(ls -A)"

bad_done
