#!/usr/bin/env bash
# Names and messages (issue 29 item 13): output names of 240 to 255 bytes are written (their temporary
# names stay within the file-name limit); a name that is not UTF-8 is refused before any work by the tools
# whose JSON records keep the command line; out of memory names the file (or image) and the size; YAML
# nested too deep says so, where; a .vdb cut short gives one message, the same every run. Each bad case:
# the exit code, the one stderr line, an unchanged work directory (lib/bad_input.sh), a peak resident
# memory under 256 MiB (GNU time).
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
source "$(dirname "${BASH_SOURCE[0]}")/lib/bad_input.sh"
source "$(dirname "${BASH_SOURCE[0]}")/lib/blob.sh"
python=/usr/bin/python3
bin=$VRI_BIN
# A command under a virtual-memory limit of 900 MB: an allocation within VRI_MAX_BYTES that the machine
# cannot give, as on a smaller machine (an array, not a function: GNU time runs programs).
small_machine=(bash -c 'ulimit -v 900000 && exec "$@"' small_machine)

# --- inputs, made before the cases: the work directory must stay as it is from here on ---
write_blob_scene
"$bin/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 8x6 -q -o a.exr
"$bin/vri-convert" -q blob_8x8x8_uint8.raw blob.vdb
{
  echo 'name: small'
  echo 'title: One render'
  echo 'paper: {paper: none, item: test, says: a test}'
  echo 'scenes: {red: {field: linear, field_dims: [5, 5, 5], convention: node, tf: tf.yaml, size: [8, 6]}}'
  echo 'methods: {riemann: {rate: 1}}'
} > run.yaml
"$python" - <<'PY'
whole = open("blob.vdb", "rb").read()
for name, keep in [("half.vdb", len(whole) // 2), ("last.vdb", len(whole) - 1), ("header.vdb", 30),
                   ("descriptor.vdb", 70), ("four.vdb", 4)]:
    open(name, "wb").write(whole[:keep])
open("deep-flow.yaml", "w").write("points: " + "[" * 300 + "]" * 300 + "\n")
open("deep-block.yaml", "w").write("".join(" " * i + "a:\n" for i in range(250)))
open("deep-map.yaml", "w").write("a: " + "{b: " * 250 + "1" + "}" * 250 + "\n")
PY
# A 1 GiB volume that takes no disk (sparse), outside the work directory (the harness hashes every file in it).
big="$VRI_SCRATCH/big_1024x1024x1024_uint8.raw"
truncate -s 1G "$big"
printf 'NRRD0004\ntype: uint8\ndimension: 3\nsizes: 1600 1600 1600\nencoding: gzip\n\n' > tiny.nrrd
"$python" -c 'import sys, zlib; sys.stdout.buffer.write(zlib.compress(bytes(100)))' >> tiny.nrrd

# --- long output names: every length up to 255 bytes is written, and nothing else is left beside it ---
out="$VRI_SCRATCH/long"
mkdir -p "$out"
for length in 239 240 247 251 255; do
  name=$(printf 'n%.0s' $(seq 1 $((length - 4))))
  "$bin/vri-tf" tf.yaml -o "$out/$name.csv" || fail "vri-tf -o a name of $length bytes"
  "$bin/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 8x6 -q -o "$out/$name.exr" \
    --stats "$out/${name:1}.json" || fail "vri-render -o a name of $length bytes"
done
[ "$(ls -A "$out" | wc -l)" -eq 15 ] || fail "long names: expected 15 files, got: $(ls -A "$out")"

# --- names that are not UTF-8, refused before any work (exit 64), the culprit escaped ---
U="is not valid UTF-8 \(byte [0-9]+\): the JSON record keeps the command line, and JSON holds UTF-8 text only$"
bad 64 "^vri-render: error: argument [0-9]+ 'bad\\\\xFF\.exr' $U" -- \
  "$bin/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 8x6 -q -o $'bad\xff.exr'
bad 64 "^vri-render: error: argument [0-9]+ 'st\\\\xFE\\\\xFE\.json' $U" -- \
  "$bin/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 8x6 -q -o out.exr --stats $'st\xfe\xfe.json'
bad 64 "^vri-reference: error: argument [0-9]+ 'p\\\\xC3\.png' $U" -- \
  "$bin/vri-reference" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 8x6 -q -o out.exr --png $'p\xc3.png'
bad 64 "^vri-render: error: argument [0-9]+ 'v\\\\xE9\.raw' $U" -- \
  "$bin/vri-render" --volume $'v\xe9.raw' --tf tf.yaml --size 8x6 -q -o out.exr
bad 64 "^vri-diff: error: argument [0-9]+ 'd\\\\xFF\.json' $U" -- "$bin/vri-diff" a.exr a.exr --json $'d\xff.json'
bad 64 "^vri-merge-tiles: error: argument [0-9]+ 'm\\\\xFF\.exr' $U" -- \
  "$bin/vri-merge-tiles" --tile a.exr a.json -o $'m\xff.exr'
bad 64 "^vri-run: error: argument [0-9]+ 'r\\\\xFF' $U" -- "$bin/vri-run" --results $'r\xff' --dry-run run.yaml

# Tools whose outputs hold no JSON take such names and write under them (exit 0): a CSV, a volume and its
# raw file, a figure whose spec names a non-UTF-8 CSV (gnuplot gets the path as a quoted string).
"$bin/vri-tf" tf.yaml -o $'t\xff.csv' || fail "vri-tf -o a non-UTF-8 name"
"$bin/vri-convert" -q blob_8x8x8_uint8.raw $'c\xff.nhdr' || fail "vri-convert to a non-UTF-8 name"
[ -s $'t\xff.csv' ] && [ -s $'c\xff.nhdr' ] && [ -s $'c\xff.raw' ] || fail "non-UTF-8 outputs missing: $(ls)"
printf 'panels:\n  - x: {label: s}\n    y: {label: tau}\n    series:\n      - {file: "t\xff.csv", x: s, y: tau}\n' > plot.yaml
"$bin/vri-plot" plot.yaml -o $'f\xfe.png' 2> plot.err || fail "vri-plot of a non-UTF-8 CSV: $(cat plot.err)"
[ -s $'f\xfe.png' ] && [ -s $'f\xfe.svg' ] || fail "vri-plot wrote no figure: $(ls)"
rm $'t\xff.csv' $'c\xff.nhdr' $'c\xff.raw' plot.yaml plot.err $'f\xfe'.*

# --- out of memory: the file or image and the size ---
# (Not under AddressSanitizer, whose shadow memory needs more address space than the ulimit leaves.)
# grep reads all of ldd's lines: with -q it stops at the match, ldd dies of SIGPIPE and pipefail fails the test.
if ! ldd "$bin/vri-render" | grep libasan > /dev/null; then
  M='needs [0-9]+ bytes: out of memory \(VRI_MAX_BYTES below the free memory refuses such sizes before allocating\)$'
  bad 1 "^vri-convert: error: .*/big_1024x1024x1024_uint8\.raw: a 1024x1024x1024 uint8 volume: needs 1073741824 bytes: out of memory" -- \
    "${small_machine[@]}" "$bin/vri-convert" --info "$big"
  bad 1 "^vri-render: error: .*/big_1024x1024x1024_uint8\.raw: a 1024x1024x1024 uint8 volume: $M" -- \
    "${small_machine[@]}" "$bin/vri-render" --volume "$big" --tf tf.yaml --size 8x6 -q -o out.exr
  bad 1 "^vri-convert: error: tiny\.nrrd: gzip data of 1600x1600x1600 uint8: needs 4096000000 bytes: out of memory" -- \
    "${small_machine[@]}" env VRI_MAX_BYTES=5000000000 "$bin/vri-convert" --info tiny.nrrd
  bad 1 "^vri-render: error: a 20000x20000 image: needs 6400000000 bytes: out of memory" -- \
    "${small_machine[@]}" env VRI_MAX_BYTES=10000000000 "$bin/vri-render" --field linear --tf tf.yaml --size 20000x20000 -q -o out.exr
fi

# --- YAML nested too deep: the limit, where ---
N='malformed YAML: collections nested deeper than 200 levels, the limit$'
bad 1 "^vri-tf: error: deep-flow\.yaml:1:208: $N" -- timeout 10 "$bin/vri-tf" deep-flow.yaml -o out.csv
bad 1 "^vri-tf: error: deep-block\.yaml:201:201: $N" -- timeout 10 "$bin/vri-tf" deep-block.yaml -o out.csv
bad 1 "^vri-render: error: deep-map\.yaml:1:[0-9]+: $N" -- timeout 10 "$bin/vri-render" --field linear --tf deep-map.yaml -q -o out.exr
bad 1 "^vri-run: error: deep-block\.yaml:201:201: $N" -- timeout 10 "$bin/vri-run" --dry-run deep-block.yaml
bad 1 "^vri-plot: error: deep-flow\.yaml:1:208: $N" -- timeout 10 "$bin/vri-plot" deep-flow.yaml -o fig.png

# --- a .vdb cut short: one message, the same on every run ---
for run in 1 2 3; do
  bad 1 "^vri-convert: error: half\.vdb: cut short: grid 0 ends at byte [0-9]+, beyond the file's end \([0-9]+ bytes\)$" -- \
    "$bin/vri-convert" --info half.vdb
  bad 1 "^vri-convert: error: four\.vdb: not a VDB file \(its first 8 bytes are not OpenVDB's magic number\)$" -- \
    "$bin/vri-convert" --info four.vdb
done
bad 1 "^vri-convert: error: last\.vdb: cut short: grid 0 ends at byte [0-9]+, beyond the file's end \([0-9]+ bytes\)$" -- \
  "$bin/vri-convert" --info last.vdb
bad 1 "^vri-convert: error: header\.vdb: cut short: the header ends at byte 57, beyond the file's end \(30 bytes\)$" -- \
  "$bin/vri-convert" --info header.vdb
bad 1 "^vri-render: error: descriptor\.vdb: cut short: grid 0's descriptor ends at byte [0-9]+, beyond the file's end \(70 bytes\)$" -- \
  "$bin/vri-render" --volume descriptor.vdb --tf tf.yaml -q -o out.exr
bad 1 "^vri-reference: error: half\.vdb: cut short: grid 0 ends at byte" -- "$bin/vri-reference" --volume half.vdb --tf tf.yaml -q -o out.exr

bad_done
