#!/usr/bin/env bash
# Bad input that asks for too much (issue 13 items 4, 8, 9): sizes that wrap or exceed a limit, work
# without a bound, and messages that must say what is wrong in one line, control characters escaped.
# Each case: the exit code, the one stderr line and an unchanged work directory (lib/bad_input.sh).
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
source "$(dirname "${BASH_SOURCE[0]}")/lib/bad_input.sh"

bin=$VRI_BIN
tf=$VRI_SOURCE/experiments/tf/paper-a-linear.yaml
render=("$bin/vri-render" --field linear --tf "$tf" -q -o out.exr)  # an array: cases run under GNU time

# --- inputs, made before the cases: the work directory must stay as it is from here on ---
"$bin/vri-render" --field linear --tf "$tf" -q --size 4x4 -o a.exr
printf '\x01\x02\x03\x04\x05\x06\x07\x08' > v_2x2x2_uint8.raw
"$bin/vri-convert" -q v_2x2x2_uint8.raw v.vdb
# vri_dims is stored uncompressed: "vri_dims", the length and name of its type ("vec3i"), its size
# (12), then x, y, z as little-endian int32.
forge_vdb() {
  cp v.vdb "$1"
  local at
  at=$(( $(grep -abo vri_dims "$1" | cut -d: -f1) + 8 + 4 + 5 + 4 ))
  printf "$2" | dd of="$1" bs=1 seek="$at" conv=notrunc status=none
}
forge_vdb wraps.vdb '\x00\x00\x40\x00\x00\x00\x40\x00\x00\x00\x10\x00'  # 4194304,4194304,1048576: 0 bytes in size_t
forge_vdb gib.vdb '\x00\x04\x00\x00\x00\x04\x00\x00\x00\x04\x00\x00'    # 1024^3 in a 10 KB file
forge_vdb cut.vdb '\x01\x00\x00\x00\x02\x00\x00\x00\x02\x00\x00\x00'    # 1x2x2: voxels outside it
printf 'Rawfile: v_2x2x2_uint8.raw\nResolution: 1e30 2 2\nFormat: UINT8\n' > huge.dat
printf 'Rawfile: v_2x2x2_uint8.raw\nResolution: 2147483647 2147483647 2147483647\nFormat: UINT8\n' > wide.dat
printf 'Rawfile: v_2x2x2_uint8.raw\nResolution: 2 2 2\nFormat: UINT8\x1b[2J\n' > escape.dat
printf 'NRRD0004\ntype: uchar\ndimension: 3\nsizes: 1e30 2 2\nencoding: raw\ndata file: v_2x2x2_uint8.raw\n' > huge.nhdr
printf 'NRRD0004\ntype: uchar\ndimension: 3\nsizes: 2 2 2\nencoding: raw\ndata file: v_2x2x2_uint8.raw\n\n' > v.nhdr
printf 'NRRD0004\ntype: uchar\ndimension: 3\nsizes: 2147483647 2147483647 2147483647\nencoding: raw\nbyte skip: -1\ndata file: v_2x2x2_uint8.raw\n' > skip.nhdr
printf 'NRRD0004\ntype: uchar\x07\ndimension: 3\nsizes: 2 2 2\nencoding: raw\ndata file: v_2x2x2_uint8.raw\n' > bell.nhdr
printf 'points:\n  - [0.0, 0.0, 0.0, 0.0, 0.0]\npo\x1bints: 3\n' > escape-tf.yaml
echo '{"channels": [{"name": "R", "above": [{"threshold": "x"}]}], "thresholds": [0.1]}' > wrong-type.json
echo '{"channels": ' > truncated.json
cp v_2x2x2_uint8.raw $'latin\xff_2x2x2_uint8.raw'  # a name that is not UTF-8
# Eight lines of YAML, 10^8 runs.
cat > sweep.yaml <<YAML
name: sweep
title: a sweep of 10^8 runs
paper: {paper: A, item: Fig. 4, says: a test}
scenes:
  s: {field: linear, field_dims: [5, 5, 5], convention: node, tf: $tf, size: [8, 8]}
methods:
  coupled: {h0: [1,2,3,4,5,6,7,8,9,10], eps: [1,2,3,4,5,6,7,8,9,10], h_max: [1,2,3,4,5,6,7,8,9,10], repeat: [1,2,3,4,5,6,7,8,9,10],
            warm_up: [1,2,3,4,5,6,7,8,9,10], h_min: [1,2,3,4,5,6,7,8,9,10], early_termination: [0,0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9], accepted: [paper, richardson], device: [a, b, c, d, e]}
YAML

# --- item 4: sizes ---
bad 1 '^vri-render: error: a 100000x100000 image of 4 float channels: needs 160000000000 bytes, limit 17179869184 \(VRI_MAX_BYTES\)$' -- "${render[@]}" --size 100000x100000
bad 1 'a 2000000000x2000000000 image .*: needs about 6\.4e\+19 bytes' -- "${render[@]}" --size 2000000000x2000000000
bad 1 '^vri-render: error: a 2097152x2097152x4194304 float32 volume: needs about 7\.38e\+19 bytes, limit 17179869184' -- "${render[@]}" --field-as-grid --field-dims 2097152,2097152,4194304
bad 1 'a 2000x2000x2000 float32 volume: needs 32000000000 bytes, limit 17179869184' -- "${render[@]}" --field-as-grid --field-dims 2000,2000,2000
bad 1 'a 100x100x100 float32 volume: needs 4000000 bytes, limit 1000000 \(VRI_MAX_BYTES\)$' -- env VRI_MAX_BYTES=1000000 "$bin/vri-render" --field linear --tf "$tf" -q -o out.exr --field-as-grid --field-dims 100,100,100
# A volume file over the limit is named, and a header's data file after the header.
bad 1 '^vri-render: error: v_2x2x2_uint8\.raw: a 2x2x2 uint8 volume: needs 8 bytes, limit 4 \(VRI_MAX_BYTES\)$' -- env VRI_MAX_BYTES=4 "$bin/vri-render" --volume v_2x2x2_uint8.raw --tf "$tf" -q -o out.exr
bad 1 '^vri-render: error: v\.nhdr: data file v_2x2x2_uint8\.raw: a 2x2x2 uint8 volume: needs 8 bytes, limit 4 \(VRI_MAX_BYTES\)$' -- env VRI_MAX_BYTES=4 "$bin/vri-render" --volume v.nhdr --tf "$tf" -q -o out.exr
bad 1 '^vri-render: error: VRI_MAX_BYTES: expected a positive byte count, got '"'"'16G'"'"'$' -- env VRI_MAX_BYTES=16G "$bin/vri-render" --field linear --tf "$tf" -q -o out.exr --size 8x8
# Read dense (--storage dense): the dense box's bytes, which wrap size_t, and the plausible size for the file.
bad 1 '^vri-convert: error: wraps\.vdb: vri_dims 4194304x4194304x1048576 \(uint8\): needs about 1\.84e\+19 bytes, limit' -- "$bin/vri-convert" --info --storage dense wraps.vdb
bad 1 'wraps\.vdb: vri_dims .*needs about 1\.84e\+19 bytes' -- "$bin/vri-render" --volume wraps.vdb --storage dense --tf "$tf" -q -o out.exr
bad 1 'wraps\.vdb: vri_dims .*needs about 1\.84e\+19 bytes' -- "$bin/vri-convert" --storage dense wraps.vdb out.raw
# Kept sparse (--storage auto, the default, for a box too large to unpack): its brick table is refused instead.
bad 1 '^vri-convert: error: wraps\.vdb: vri_dims 4194304x4194304x1048576 \(uint8\) kept sparse, its brick table: needs 144115188075855872 bytes, limit' -- "$bin/vri-convert" --info wraps.vdb
bad 1 'wraps\.vdb: vri_dims .* kept sparse, its brick table: needs 144115188075855872 bytes' -- "$bin/vri-render" --volume wraps.vdb --tf "$tf" -q -o out.exr
bad 1 '^vri-convert: error: gib\.vdb: vri_dims 1024x1024x1024 \(uint8\): needs 1073741824 bytes, limit 268435456 for a file of [0-9]+ bytes' -- "$bin/vri-convert" --info --storage dense gib.vdb
bad 1 'gib\.vdb: .*for a file of' -- "$bin/vri-render" --volume gib.vdb --storage dense --tf "$tf" -q -o out.exr
bad 1 'cut\.vdb: vri_dims 1x2x2 does not contain the active voxels \(0,0,0\)\.\.\(1,1,1\)$' -- "$bin/vri-convert" --info cut.vdb
bad 1 'huge\.dat:2: Resolution: expected three positive integers up to 2147483647' -- "$bin/vri-convert" --info huge.dat
bad 1 'wide\.dat: Rawfile v_2x2x2_uint8\.raw: 2147483647x2147483647x2147483647 uint8 needs more than 2\^64 bytes$' -- "$bin/vri-convert" --info wide.dat
bad 1 'huge\.nhdr:4: sizes: sizes must be positive integers up to 2147483647' -- "$bin/vri-convert" --info huge.nhdr
bad 1 'skip\.nhdr: data file .*needs more than 2\^64 bytes$' -- "$bin/vri-convert" --info skip.nhdr
bad 1 'raw.*file is 8 bytes, expected 1000000000000000000' -- "$bin/vri-convert" --info v_2x2x2_uint8.raw --dims 1000000,1000000,1000000 --type uint8
# The last resort: an allocation the limits allowed and the machine does not have. (Not under
# AddressSanitizer, whose shadow memory needs more address space than the ulimit leaves.)
# grep reads all of ldd's lines: with -q it stops at the match, ldd dies of SIGPIPE and pipefail fails the test.
if ! ldd "$bin/vri-render" | grep libasan > /dev/null; then
  bad 1 '^vri-render: error: a 60000x60000 image: needs 57600000000 bytes: out of memory' -- bash -c \
    'ulimit -v 4000000; VRI_MAX_BYTES=100000000000 exec "$0" --field linear --tf "$1" -q -o out.exr --size 60000x60000' "$bin/vri-render" "$tf"
fi

# --- item 8: unbounded work ---
bad 1 '^vri-render: error: h_min 1e-300 would allow more than 1e9 steps on a ray through this volume$' -- "${render[@]}" --method coupled --h-min 1e-300 --tolerance 0
bad 1 'h_min 1e-300 would allow more than 1e9 steps' -- "${render[@]}" --method decoupled --h-min 1e-300 --h0 1e-300 --tolerance 0
bad 1 'sampling rate .* would put more than 1e9 samples on a ray' -- "${render[@]}" --step 1e-12
bad 1 'step 1e-06 would allow more than 2\^22 steps on a ray through this volume in float precision' -- "${render[@]}" --method simpson --step 1e-6 --precision float
bad 1 'h_min 1e-07 would allow more than 2\^22 steps .* in float precision' -- "${render[@]}" --method coupled --h-min 1e-7 --precision float
bad 1 'h_min 1e-300 would allow' -- "$bin/vri-render" --volume v_2x2x2_uint8.raw --tf "$tf" -q -o out.exr --method coupled --h-min 1e-300
bad 1 '^vri-rays2d: error: 2D study: the fan: needs 2000000000 rays, limit 1000000$' -- "$bin/vri-rays2d" -o rays.csv --rays 2000000000
bad 1 '^vri-rays2d: error: 2D study: 120 rays x 4 placements at rates summing to 1e\+12 on a 5x5 grid: needs 4354112549695428 samples, limit 1000000000$' -- "$bin/vri-rays2d" -o rays.csv --rates 1e12
bad 1 'at rates summing to 1e\+09 .*limit 1000000000' -- "$bin/vri-rays2d" --errors errors.md --rates 1e9 --placements entry
bad 1 '^vri-rays2d: error: field image of 100000x100000 points: needs 10000000000 points \(rows\), limit 4194304$' -- "$bin/vri-rays2d" --field-image field.csv --field-resolution 100000
bad 1 '^vri-rays2d: error: diagram: 6 rays x 4 placements at rate 1e\+09: needs 217705627484 samples, limit 1000000$' -- "$bin/vri-rays2d" --diagram fig1.csv --diagram-rate 1e9
bad 1 'diagram: .*needs unboundedly many samples' -- "$bin/vri-rays2d" --diagram fig1.csv --diagram-rate inf
bad 1 'a 100000x100000x1 float32 volume: needs 40000000000 bytes' -- "$bin/vri-rays2d" -o rays.csv --grid 100000
bad 1 "^vri-run: error: sweep\.yaml:7:[0-9]+: methods entry 'coupled': needs 100000000 runs, limit 10000$" -- "$bin/vri-run" --dry-run sweep.yaml
bad 1 "sweep\.yaml:7:[0-9]+: methods entry 'coupled': needs 100000000 runs, limit 10000$" -- "$bin/vri-run" --results results sweep.yaml
bad 64 '^vri-diff: error: logarithmic bins from 1e-300 to 1e\+300 at 100000000 per decade: needs 60000000000 bins, limit 1000000$' -- \
  "$bin/vri-diff" a.exr a.exr --histogram histogram.csv --histogram-range 1e-300,1e300 --bins-per-decade 100000000

# --- item 9: messages ---
bad 1 '^vri-render: error: camera eye 1e\+308,0,0: coordinates must be finite and at most 1e\+150 in magnitude$' -- "${render[@]}" --eye 1e308,0,0
bad 1 'camera target 0,1e\+200,0: coordinates must be finite' -- "${render[@]}" --target 0,1e200,0
bad 1 'camera up vector 0,0,0 is zero or shorter than 1e-150$' -- "${render[@]}" --up 0,0,0
bad 1 'camera eye and target coincide at 1,2,3$' -- "${render[@]}" --eye 1,2,3 --target 1,2,3
bad 1 'camera up vector is parallel to the view direction$' -- "${render[@]}" --eye 0,0,5 --target 0,0,0 --up 0,0,1
bad 1 'camera eye and target are only [0-9.e+-]+ apart, below the 1e-150 the camera resolves \(is the scene, e\.g\. its voxel spacing, that small\?\)$' -- \
  "$bin/vri-render" --volume v_2x2x2_uint8.raw --tf "$tf" -q -o out.exr --spacing 1e-300,1e-300,1e-300
bad 1 'camera eye [0-9.e+,-]+: coordinates must be finite and at most 1e\+150' -- \
  "$bin/vri-render" --volume v_2x2x2_uint8.raw --tf "$tf" -q -o out.exr --spacing 1e300,1e300,1e300
bad 1 "escape\.dat:3: Format: unknown voxel type 'UINT8\\\\x1b\[2J'" -- "$bin/vri-convert" --info escape.dat
bad 1 "bell\.nhdr:2: type: 'uchar\\\\x07' is not supported" -- "$bin/vri-convert" --info bell.nhdr
bad 1 "escape-tf\.yaml:3:1: unknown key 'po\\\\x1bints'" -- "$bin/vri-render" --field linear --tf escape-tf.yaml -q -o out.exr
bad 1 "--method: unknown method 'x\\\\x0ay'" -- "${render[@]}" --method $'x\ny'
bad nonzero "--size: expected a positive image size WIDTHxHEIGHT, got '1x\\\\x1b1'" -- "${render[@]}" --size $'1x\e1'
bad 1 '^vri-tabulate: error: wrong-type\.json: channels\.0\.above\.0\.threshold: type must be number, but is string$' -- "$bin/vri-tabulate" --layout thresholds --row a wrong-type.json -o table.md
bad 1 '^vri-tabulate: error: truncated\.json: not valid JSON: parse error at line 2, column 1: syntax error while parsing value - unexpected end of input' -- "$bin/vri-tabulate" --layout thresholds --row a truncated.json -o table.md
bad 1 '^vri-run: error: missing-dir: No such file or directory$' -- "$bin/vri-run" --gallery missing-dir
bad 64 "^vri-convert: error: argument 3 'latin\\\\xFF_2x2x2_uint8\.raw' is not valid UTF-8 \(byte 5\): --json names the input, and JSON holds UTF-8 text only$" -- \
  "$bin/vri-convert" --info --json $'latin\xff_2x2x2_uint8.raw'

bad_done
