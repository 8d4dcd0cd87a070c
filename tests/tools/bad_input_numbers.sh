#!/usr/bin/env bash
# Bad numbers and contradictory outputs (issue 13 item 7): each case exits non-zero with one error line
# naming the file, line, field or argument, and leaves the work directory as it was. Renders whose
# pixels overflow, float volumes holding NaN or infinity, empty or inverted value ranges, spacings and
# byte offsets out of range, YAML keys given twice, and -o/--png/--stats naming one file.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
source "$(dirname "${BASH_SOURCE[0]}")/lib/bad_input.sh"
source "$(dirname "${BASH_SOURCE[0]}")/lib/blob.sh" && write_blob_scene

render=("$VRI_BIN/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 16x12 -q)
reference=("$VRI_BIN/vri-reference" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 16x12 -q)

# Outputs: the image is float EXR, and no two outputs may be one file, however it is spelled.
mkdir sub
bad 64 "^vri-render: error: -o: 'x\.png' is not an \.exr file" -- "${render[@]}" -o x.png
bad 64 "^vri-render: error: -o: 'x' is not an \.exr file" -- "${render[@]}" -o x --allow-nonfinite
bad 64 "^vri-render: error: --png: 'a\.exr' is also -o's output" -- "${render[@]}" -o a.exr --png a.exr
bad 64 "^vri-render: error: --stats: '\./a\.exr' is also -o's output" -- "${render[@]}" -o a.exr --stats ./a.exr
bad 64 "^vri-render: error: --png: 'a\.exr' is also -o's output" -- "${render[@]}" -o sub/../a.exr --png a.exr
bad 64 "^vri-render: error: --stats: '$PWD/p\.png' is also --png's output" -- \
  "${render[@]}" -o a.exr --png p.png --stats "$PWD/p.png"
bad 64 "^vri-render: error: --stats: '-' \(standard output\) is also --png's output" -- \
  "${render[@]}" -o a.exr --png - --stats -
bad 64 "^vri-reference: error: --stats: '-' \(standard output\) is also --png's output" -- \
  "${reference[@]}" -o r.exr --png - --stats -
bad 64 "^vri-reference: error: -o: 'r\.tif' is not an \.exr file" -- "${reference[@]}" -o r.tif
bad 64 "^vri-reference: error: --error-image: 'e\.png' is not an \.exr file" -- "${reference[@]}" -o r.exr --error-image e.png
bad 64 "^vri-reference: error: --error-image: 'r\.exr' is also -o's output" -- "${reference[@]}" -o r.exr --error-image r.exr
bad 64 "^vri-reference: error: --png: 'r\.exr' is also -o's output" -- \
  "${reference[@]}" --method riemann --step 0.1 -o r.exr --png r.exr
bad 64 "^vri-sampler-probe: error: --summary: '\./s\.csv' is also -o's output" -- \
  "$VRI_BIN/vri-sampler-probe" -q -o s.csv --summary ./s.csv

# Overflowing renders: refused up front in float, found after the render otherwise.
printf 'points:\n  - [0.0, 0, 0, 0, 0]\n  - [0.3, 0, 0, 0, 0]\n  - [0.7, 1, 0.5, 0.2, 1e300]\n  - [1.0, 1, 1, 1, 1e300]\n' > huge.yaml
huge=("$VRI_BIN/vri-render" --volume blob_8x8x8_uint8.raw --tf huge.yaml --size 16x12 -q -o h.exr --png h.png --stats h.json)
bad 1 "^vri-render: error: the image: [0-9]+ of 192 pixels are not finite \(first at [0-9]+,[0-9]+: R=inf" -- "${huge[@]}"
bad 1 "^vri-render: error: the image: [0-9]+ of 192 pixels are not finite \(first at [0-9]+,[0-9]+: R=nan" -- \
  "${huge[@]}" --method coupled
bad 1 "^vri-render: error: transfer function point 2 holds 1e\+300, beyond the range of float" -- \
  "${huge[@]}" --precision float
bad 1 "^vri-reference: error: the image: [0-9]+ of 192 pixels are not finite" -- \
  "$VRI_BIN/vri-reference" --volume blob_8x8x8_uint8.raw --tf huge.yaml --size 16x12 -q --method riemann --step 0.1 -o h.exr

# Float volumes holding NaN or infinity, in each format that carries float voxels.
{ printf '\x00\x00\x80\x3f%.0s' $(seq 1 12); printf '\x00\x00\xc0\x7f'; printf '\x00\x00\x80\x3f%.0s' $(seq 1 14); } \
  > nan_3x3x3_float32.raw
{ printf '\x00\x00\x80\x3f%.0s' $(seq 1 26); printf '\x00\x00\x80\xff'; } > inf.raw
bad 1 "nan_3x3x3_float32\.raw: voxel 12 \(x 0, y 1, z 1\) is nan: float volumes must hold finite values" -- \
  "$VRI_BIN/vri-render" --volume nan_3x3x3_float32.raw --tf tf.yaml --size 16x12 -q -o n.exr
bad 1 "inf\.raw: voxel 26 \(x 2, y 2, z 2\) is -inf" -- "$VRI_BIN/vri-convert" --info inf.raw --dims 3,3,3 --type float32
printf 'NRRD0004\ntype: float\ndimension: 3\nsizes: 3 3 3\nencoding: raw\nendian: little\ndata file: inf.raw\n' > inf.nhdr
bad 1 "inf\.nhdr: voxel 26 \(x 2, y 2, z 2\) is -inf" -- "$VRI_BIN/vri-convert" --info inf.nhdr
printf 'Rawfile: nan_3x3x3_float32.raw\nResolution: 3 3 3\nFormat: FLOAT32\n' > nan.dat
bad 1 "nan\.dat: voxel 12 .* is nan" -- "$VRI_BIN/vri-convert" nan.dat out.vdb

# .dat values: empty or inverted ranges, a byte offset that is not an integer, a box beyond double.
dat() {  # dat NAME LINE...: a .dat header for the blob with the given extra lines
  local name=$1
  shift
  { printf 'Rawfile: blob_8x8x8_uint8.raw\nResolution: 8 8 8\nFormat: UINT8\n'; printf '%s\n' "$@"; } > "$name"
}
dat empty.dat "DataRange: 5 5"
bad 1 "^vri-convert: error: .*empty\.dat:4: DataRange: expected lo < hi, got '5 5'" -- "$VRI_BIN/vri-convert" --info empty.dat
dat inverted.dat "ByteOrder: LittleEndian" "DataRange: 255 0"
bad 1 "inverted\.dat:5: DataRange: expected lo < hi, got '255 0'" -- \
  "$VRI_BIN/vri-render" --volume inverted.dat --tf tf.yaml --size 16x12 -q -o i.exr
dat offset.dat "ByteOffset: 1e30"
bad 1 "offset\.dat:4: ByteOffset: expected a byte count \(a whole number, 0 or more\), got '1e30'" -- \
  "$VRI_BIN/vri-convert" --info offset.dat
dat negative.dat "ByteOffset: -8"
bad 1 "negative\.dat:4: ByteOffset: expected a byte count" -- "$VRI_BIN/vri-convert" --info negative.dat
dat far.dat "Offset: 1e308 0 0" "BasisVector1: 1e308 0 0" "BasisVector2: 0 8 0" "BasisVector3: 0 0 8"
bad 1 "far\.dat: the box \(origin 1e\+308 \+ 8 voxels x spacing .* along x\) is beyond the range of a double" -- \
  "$VRI_BIN/vri-convert" --info far.dat

bad 1 "^vri-render: error: --spacing 1,1e308,1: the box \(origin 0 \+ 8 voxels x spacing 1e\+308 along y\) is beyond" -- \
  "$VRI_BIN/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 16x12 -q -o s.exr --spacing 1,1e308,1

# .nhdr spacings: beyond double once multiplied out, zero, negative, not a number.
nhdr() {  # nhdr NAME LINE: a detached header for the blob with one extra line (line 8)
  printf 'NRRD0004\ntype: uchar\ndimension: 3\nsizes: 8 8 8\nencoding: raw\ndata file: blob_8x8x8_uint8.raw\n# x\n%s\n' \
    "$2" > "$1"
}
nhdr huge.nhdr "spacings: 1 1e308 1"
bad 1 "huge\.nhdr:8: spacings: spacing 1e\+308 along y must be positive, and times 8 voxels within the range of a double" -- \
  "$VRI_BIN/vri-render" --volume huge.nhdr --tf tf.yaml --size 16x12 -q -o s.exr
nhdr zero.nhdr "spacings: 0 1 1"
bad 1 "zero\.nhdr:8: spacings: spacing 0 along x must be positive" -- "$VRI_BIN/vri-convert" --info zero.nhdr
nhdr negative.nhdr "space directions: (1,0,0) (0,1,0) (0,0,-2)"
bad 1 "negative\.nhdr:8: space directions: only axis-aligned grids with positive directions" -- \
  "$VRI_BIN/vri-convert" --info negative.nhdr
nhdr nan.nhdr "spacings: 1 nan 1"
bad 1 "nan\.nhdr:8: spacings: 'nan' is not a finite number" -- "$VRI_BIN/vri-convert" --info nan.nhdr
nhdr range.nhdr "vri_range:=9 2"
bad 1 "range\.nhdr:8: vri_range: expected lo < hi, got '9 2'" -- "$VRI_BIN/vri-convert" --info range.nhdr
nhdr skip.nhdr "byte skip: 1e30"
bad 1 "skip\.nhdr:8: byte skip: expected a byte count" -- "$VRI_BIN/vri-convert" --info skip.nhdr

# YAML keys given twice: both lines named.
printf 'points:\n  - [0, 0, 0, 0, 0]\n  - [1, 1, 1, 1, 1]\nemission: color\npoints:\n  - [0, 1, 1, 1, 1]\n' > twice.yaml
bad 1 "^vri-render: error: twice\.yaml:5:1: duplicate key 'points' \(first at line 1\)$" -- \
  "$VRI_BIN/vri-render" --volume blob_8x8x8_uint8.raw --tf twice.yaml --size 16x12 -q -o t.exr
bad 1 "^vri-tf: error: twice\.yaml:5:1: duplicate key 'points' \(first at line 1\)$" -- "$VRI_BIN/vri-tf" twice.yaml -o t.csv
printf 'points:\n  - {s: 0, color: [0, 0, 0], tau: 0}\n  - {s: 1, color: [1, 1, 1], tau: 1, color: [0, 0, 0]}\n' > nested.yaml
bad 1 "nested\.yaml:3:38: duplicate key 'color' \(first at line 3\)" -- "$VRI_BIN/vri-tf" nested.yaml -o t.csv
cat > experiment.yaml <<'YAML'
name: twice
title: Twice
paper: {paper: A, item: Fig. 4, says: steps}
scenes:
  s: {field: linear, convention: node, tf: tf.yaml, size: [8, 8]}
methods:
  riemann: {rate: 1}
methods:
  composite: {rate: 1}
YAML
bad 1 "^vri-run: error: experiment\.yaml:8:1: duplicate key 'methods' \(first at line 6\)$" -- \
  "$VRI_BIN/vri-run" --dry-run experiment.yaml --results results

# Hexadecimal numbers are numbers to every option, whether vri or CLI11 converts it: --step 0x1p-1 is
# --step 0.5, bit for bit; a hexadecimal that is not a number is refused like any other.
"${render[@]}" --step 0x1p-1 --repeat 0x2 -o hex.exr || fail "--step 0x1p-1 --repeat 0x2 refused"
"${render[@]}" --step 0.5 -o dec.exr
"$VRI_BIN/vri-diff" hex.exr dec.exr --fail 0 > /dev/null || fail "--step 0x1p-1 differs from --step 0.5"
bad 64 "^vri-render: error: --step: expected a number, got '0x1q' \(see --help\)$" -- "${render[@]}" --step 0x1q -o q.exr

# The options CLI11 converts itself read numbers as the others do: a leading 0 is not octal (strtoll's base 0
# would read 010 as 8 and refuse 08), and spaces, an empty value, a plus or an integer beyond 64 bits are
# refused, where CLI11 would skip the spaces, read 0, or clamp (inf is a number: the option says its range).
I="expected an integer \(decimal, or hexadecimal after 0x\)"
bad 1 "after a 10-byte header$" -- "${render[@]}" --header-bytes 010 -o z.exr
bad 1 "after a 8-byte header$" -- "${render[@]}" --header-bytes 08 -o z.exr
bad 1 "after a 16-byte header$" -- "${render[@]}" --header-bytes 0x10 -o z.exr
bad 64 "^vri-render: error: --header-bytes: $I, got '1e3' \(see --help\)$" -- "${render[@]}" --header-bytes 1e3 -o z.exr
bad 64 "^vri-render: error: --header-bytes: $I, got ' 010' \(see --help\)$" -- "${render[@]}" --header-bytes ' 010' -o z.exr
bad 64 "^vri-render: error: --header-bytes: $I, got '' \(see --help\)$" -- "${render[@]}" --header-bytes '' -o z.exr
bad 64 "^vri-render: error: --header-bytes: $I, got '\+8' \(see --help\)$" -- "${render[@]}" --header-bytes +8 -o z.exr
bad 64 "^vri-render: error: --header-bytes: 99999999999999999999 is outside the range of this integer option" -- \
  "${render[@]}" --header-bytes 99999999999999999999 -o z.exr
bad 64 "^vri-render: error: --threads: 4294967296 is outside the range of this integer option" -- \
  "${render[@]}" --threads 0x100000000 -o z.exr
bad 1 "^vri-render: error: --fov: expected degrees in \(0, 180\), got inf$" -- "${render[@]}" --fov inf -o z.exr
bad 64 "^vri-render: error: --fov: expected a number, got ' 30' \(see --help\)$" -- "${render[@]}" --fov ' 30' -o z.exr
# CLI11 reads a FLOAT option through long double, which rounds this decimal (just above the midpoint between 1
# and the next double) to the midpoint and then to 1; it is read as the nearest double, 1 + 2^-52, as parse.h reads.
"${render[@]}" --fov 1.000000000000000111022302462515654042363166809082031250001 -o fov.exr --stats fov.json
grep -q '"fov_y_degrees": 1.0000000000000002,' fov.json || fail "--fov's long decimal was not read as the nearest double"
# A size's sides are decimal: 'x' separates them, so 0X10x8 is not 16x8.
bad 1 "^vri-render: error: --size: expected a positive image size WIDTHxHEIGHT, got '0X10x8'$" -- \
  "$VRI_BIN/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 0X10x8 -q -o z.exr

bad_done
