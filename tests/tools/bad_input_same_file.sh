#!/usr/bin/env bash
# An output that names one of the command's own inputs (issue 29, item 11): writing it would destroy what
# is being read, so every tool refuses it before any work, exit 64, with the one line
# "<tool>: error: <output option> 'PATH' is the same file as <input option> 'PATH'", whatever the spelling
# (relative or absolute, a symbolic or a hard link) and for the data file a volume header names; nothing
# is written or replaced.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
source "$(dirname "${BASH_SOURCE[0]}")/lib/bad_input.sh"
source "$(dirname "${BASH_SOURCE[0]}")/lib/blob.sh"
bin=${VRI_BIN:?}

# Inputs, in the work directory (each case checks that it is left exactly as it was).
write_blob_scene
vol=blob_8x8x8_uint8.raw
"$bin/vri-render" --volume "$vol" --tf tf.yaml --size 8x8 -q -o a.exr --stats stats.json
"$bin/vri-render" --volume "$vol" --tf tf.yaml --size 8x8 -q -o b.exr --step 0.25
"$bin/vri-diff" a.exr b.exr --json diff.json > /dev/null || true
printf 'NRRD0004\ntype: uint8\ndimension: 3\nsizes: 8 8 8\nencoding: raw\ndata file: %s\n' "$vol" > v.nhdr
printf 'NDims = 3\nDimSize = 8 8 8\nElementType = MET_UCHAR\nElementDataFile = %s\n' "$vol" > v.mhd
printf 'Rawfile: %s\nResolution: 8 8 8\nFormat: UINT8\n' "$vol" > v.dat
printf 'a,b\n1,2\n2,3\n' > data.csv
printf 'panels:\n  - title: x\n    series:\n      - {file: data.csv, x: a, y: b, style: line}\n' > spec.yaml
cp spec.yaml spec.gp
mkdir sub
ln -s tf.yaml tf-link.json
ln "$vol" hard.json
ln -s data.csv fig.svg
render=("$bin/vri-render" --volume "$vol" --tf tf.yaml --size 8x8 -q -o out.exr)
same="is the same file as"

E='^vri-render: error: '
bad 64 "${E}--stats '$vol' $same --volume '$vol'\$" -- "${render[@]}" --stats "$vol"
bad 64 "${E}--stats 'tf-link\.json' $same --tf 'tf\.yaml'\$" -- "${render[@]}" --stats tf-link.json
bad 64 "${E}--png '$PWD/tf\.yaml' $same --tf 'tf\.yaml'\$" -- "${render[@]}" --png "$PWD/tf.yaml"
bad 64 "${E}--stats 'hard\.json' $same --volume '$vol'\$" -- "${render[@]}" --stats hard.json
bad 64 "${E}--stats '$vol' $same --volume's data file '$vol'\$" -- \
    "$bin/vri-render" --volume v.nhdr --tf tf.yaml --size 8x8 -q -o out.exr --stats "$vol"
bad 64 "${E}-o 'a\.exr' $same --tf 'a\.exr'\$" -- "$bin/vri-render" --volume "$vol" --tf a.exr --size 8x8 -q -o a.exr
E='^vri-reference: error: '
bad 64 "${E}--stats 'sub/\.\./hard\.json' $same --volume '$PWD/$vol'\$" -- \
    "$bin/vri-reference" --volume "$PWD/$vol" --tf tf.yaml --size 8x8 -q -o out.exr --stats sub/../hard.json
E='^vri-tf: error: '
bad 64 "${E}-o 'tf\.yaml' $same TF 'tf\.yaml'\$" -- "$bin/vri-tf" tf.yaml -o tf.yaml
bad 64 "${E}-o 'tf-link\.json' $same TF '\./tf\.yaml'\$" -- "$bin/vri-tf" ./tf.yaml -o tf-link.json
E='^vri-diff: error: '
bad 64 "${E}--diff-image 'a\.exr' $same A 'a\.exr'\$" -- "$bin/vri-diff" a.exr b.exr --diff-image a.exr
bad 64 "${E}--json '$PWD/b\.exr' $same B 'b\.exr'\$" -- "$bin/vri-diff" a.exr b.exr --json "$PWD/b.exr"
E='^vri-tabulate: error: '
bad 64 "${E}-o 'diff\.json' $same --row 'diff\.json'\$" -- "$bin/vri-tabulate" --layout thresholds --row x diff.json -o diff.json
bad 64 "${E}--csv 'stats\.json' $same --run 'stats\.json'\$" -- \
    "$bin/vri-tabulate" --layout tradeoff --run x stats.json diff.json -o t.md --csv stats.json
E='^vri-plot: error: '
bad 64 "${E}-o's script 'spec\.gp' $same SPEC 'spec\.gp'\$" -- "$bin/vri-plot" spec.gp -o spec.png --script-only
bad 64 "${E}-o's SVG 'fig\.svg' $same SPEC's data file '.*data\.csv'\$" -- "$bin/vri-plot" spec.yaml -o fig.png
E='^vri-merge-tiles: error: '
bad 64 "${E}--stats 'stats\.json' $same --tile 'stats\.json'\$" -- \
    "$bin/vri-merge-tiles" --tile a.exr stats.json -o out.exr --stats stats.json
E='^vri-convert: error: '
bad 64 "${E}output '$vol' $same input '$vol'\$" -- "$bin/vri-convert" "$vol" "$vol"
bad 64 "${E}output 'hard\.json' $same input '$vol'\$" -- "$bin/vri-convert" "$vol" hard.json
# A header and the output's raw file: v.nhdr names blob_8x8x8_uint8.raw, which blob_8x8x8_uint8.nhdr writes.
for header in v.nhdr v.mhd v.dat; do
  bad 64 "${E}output's raw file 'blob_8x8x8_uint8\.raw' $same input's data file '$vol'\$" -- \
      "$bin/vri-convert" "$header" blob_8x8x8_uint8.nhdr
done
bad 64 "${E}output's raw file '$PWD/blob_8x8x8_uint8\.raw' $same input's data file '$vol'\$" -- \
    "$bin/vri-convert" v.nhdr "$PWD/blob_8x8x8_uint8.dat"
bad 64 "${E}output 'v\.nhdr' $same input 'v\.nhdr'\$" -- "$bin/vri-convert" v.nhdr v.nhdr

bad_done
