#!/usr/bin/env bash
# Bad input to the peer adapter vri-peer-vtk: one error line, exit 64 for a bad argument and 1 for a bad file or
# output, nothing written (a directory, FIFO or device given as an output is refused before any work).
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
source "$(dirname "${BASH_SOURCE[0]}")/lib/bad_input.sh"
/usr/bin/python3 -c 'import vtk, numpy, OpenImageIO, yaml' 2>/dev/null ||
    { echo "python3-vtk9, python3-numpy, python3-openimageio or python3-yaml not installed: skipping"; exit 77; }
command -v xvfb-run >/dev/null || [ -n "${DISPLAY:-}" ] || { echo "no X display and no xvfb-run (xvfb): skipping"; exit 77; }
peer=$VRI_BIN/vri-peer-vtk
source "$VRI_SOURCE/tests/tools/lib/blob.sh" && write_blob_scene
printf 'points:\n  - [0.5, 0, 0, 0, 0]\n  - [0.1, 0, 0, 0, 0]\n' > unsorted.yaml
printf 'emission: color\npoints:\n  - [0, 0, 0, 0, 0]\n  - [1, 1, 1, 1, 1]\n' > colour.yaml
mkdir taken.exr
mkfifo stream.exr
scene=(--volume blob_8x8x8_uint8.raw --tf tf.yaml --size 8x6 --eye 4,4,-20 --target 4,4,4 -q)

bad 64 '^vri-peer-vtk: error: the following arguments are required: --volume' -- "$peer" --tf tf.yaml -o out.exr
bad 64 '^vri-peer-vtk: error: The following argument was not expected: --zoom' -- "$peer" "${scene[@]}" --zoom 2 -o out.exr
bad 64 "^vri-peer-vtk: error: argument --method: invalid choice: 'vtk-raycast'" -- \
    "$peer" "${scene[@]}" --method vtk-raycast -o out.exr
bad 64 "^vri-peer-vtk: error: --size '0x6': expected WIDTHxHEIGHT" -- "$peer" "${scene[@]}" --size 0x6 -o out.exr
bad 64 '^vri-peer-vtk: error: --size 65536x65536: 4294967296 pixels, limit 268435456$' -- \
    "$peer" "${scene[@]}" --size 65536x65536 -o out.exr
bad 64 "^vri-peer-vtk: error: --eye '4,4': expected 3 finite numbers" -- "$peer" "${scene[@]}" --eye 4,4 -o out.exr
bad 64 "^vri-peer-vtk: error: --target 'nan,0,0': expected 3 finite numbers" -- \
    "$peer" "${scene[@]}" --target nan,0,0 -o out.exr
bad 64 '^vri-peer-vtk: error: --step 0: expected a number > 0$' -- "$peer" "${scene[@]}" --step 0 -o out.exr
bad 64 '^vri-peer-vtk: error: --fov 180: expected degrees in \(0, 180\)$' -- "$peer" "${scene[@]}" --fov 180 -o out.exr
bad 64 '^vri-peer-vtk: error: --repeat 0: expected a whole number in 1..1000$' -- "$peer" "${scene[@]}" --repeat 0 -o out.exr
# Numbers as vri's tools read them (parse.h): hexadecimal after 0x is a number, a leading 0 is not octal, and
# spaces, underscores, a plus and digits other than ASCII's are not numbers.
bad 64 '^vri-peer-vtk: error: --repeat 4096: expected a whole number in 1..1000$' -- "$peer" "${scene[@]}" --repeat 0x1000 -o out.exr
bad 64 '^vri-peer-vtk: error: --repeat 1010: expected a whole number in 1..1000$' -- "$peer" "${scene[@]}" --repeat 01010 -o out.exr
bad 64 '^vri-peer-vtk: error: --fov 256: expected degrees in \(0, 180\)$' -- "$peer" "${scene[@]}" --fov 0x1p8 -o out.exr
# An option's value may start with '-', as in vri's tools: it is the value, not an unknown option.
bad 64 '^vri-peer-vtk: error: --fov -5: expected degrees in \(0, 180\)$' -- "$peer" "${scene[@]}" --fov -5 -o out.exr
"$peer" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 8x6 --eye -20,4,4 --target 4,4,4 -q -o negative.exr ||
    fail "--eye -20,4,4 refused"
literal() { printf '%s' "$1" | sed 's/[].+*?^$()[{}|\\]/\\&/g'; }  # text as a regex that matches it alone
for text in ' 3' 1_0 +3 '٣' '' 3.0; do
    bad 64 "^vri-peer-vtk: error: argument --warm-up: expected an integer \(decimal, or hexadecimal after 0x\), got '$(literal "$text")'" -- \
        "$peer" "${scene[@]}" --warm-up "$text" -o out.exr
done
for text in ' 30' 1_0 +30 '' 0x1q 1e999 1e-999 0x1p-1080; do  # 1e-999 would read as 0: beyond double, as in parse.h
    bad 64 "^vri-peer-vtk: error: argument --fov: expected a number, got '$(literal "$text")'" -- "$peer" "${scene[@]}" --fov "$text" -o out.exr
done
bad 64 '^vri-peer-vtk: error: --image raycast: only vtk-fixed-point' -- \
    "$peer" "${scene[@]}" --method vtk-gpu --image raycast -o out.exr
bad 64 '^vri-peer-vtk: error: -o out.png: expected an .exr file$' -- "$peer" "${scene[@]}" -o out.png
bad 64 '^vri-peer-vtk: error: -o, --png and --stats must name different files$' -- \
    "$peer" "${scene[@]}" -o out.exr --stats out.exr
bad 64 '^vri-peer-vtk: error: --step 1e-09 would put more than 1e9 samples on a ray' -- \
    "$peer" "${scene[@]}" --step 1e-9 -o out.exr
bad 1 '^vri-peer-vtk: error: taken\.exr: cannot write: it is a directory; expected a regular file$' -- \
    "$peer" "${scene[@]}" -o taken.exr
bad 1 '^vri-peer-vtk: error: stream\.exr: cannot write: it is not a regular file' -- "$peer" "${scene[@]}" -o stream.exr
bad 1 '^vri-peer-vtk: error: missing/out\.exr: cannot write: no such folder$' -- "$peer" "${scene[@]}" -o missing/out.exr
bad 1 '^vri-peer-vtk: error: nope\.raw: no such file$' -- \
    "$peer" --volume nope.raw --tf tf.yaml --eye 4,4,-20 --target 4,4,4 -q -o out.exr
bad 1 "^vri-peer-vtk: error: unsorted\.yaml:3:5: points\[1\] has s = 0\.1 below the previous point's" -- \
    "$peer" --volume blob_8x8x8_uint8.raw --tf unsorted.yaml --eye 4,4,-20 --target 4,4,4 -q -o out.exr
bad 1 '^vri-peer-vtk: error: colour\.yaml: emission color: VTK composites colour times opacity' -- \
    "$peer" --volume blob_8x8x8_uint8.raw --tf colour.yaml --eye 4,4,-20 --target 4,4,4 -q -o out.exr
bad_done
