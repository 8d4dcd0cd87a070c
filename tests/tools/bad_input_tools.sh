#!/usr/bin/env bash
# Bad input that every tool already rejects cleanly, kept that way: bad flags, missing and malformed
# files, malformed numbers and lists, unknown names, options that do not go together. Each case asserts
# the exit code (1 for a bad input or value, 64 for what CLI11's parser rejects, vri-diff's 4 for
# images of different shapes), the one line on stderr, and that the work directory is unchanged.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
source "$(dirname "${BASH_SOURCE[0]}")/lib/bad_input.sh"
source "$(dirname "${BASH_SOURCE[0]}")/lib/blob.sh"

bin="$VRI_BIN"

# The inputs, in the work directory (the harness checks that no case changes them).
write_blob_scene
"$bin/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 8x8 -o a.exr -q --png a.png
"$bin/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 4x4 -o small.exr -q --stats stats.json
"$bin/vri-diff" a.exr a.exr --json diff.json > /dev/null
echo "not an image" > junk.exr
printf 'not a vdb' > junk.vdb
printf '{"a": 1\n' > broken.json
printf 'points:\n  - [0, 0, 0, 0, -1]\n' > negative_tau.yaml
printf 'points: [[0, 0, 0, 0, 0]\n' > unclosed_tf.yaml
printf 'NRRD0004\ntype: uint8\ndimension: 2\nsizes: 8 8\nencoding: raw\ndata file: blob_8x8x8_uint8.raw\n' > flat.nhdr
printf 'NRRD0004\ntype: uint8\ndimension: 3\nsizes: 8 8 8\nencoding: bzip2\ndata file: blob_8x8x8_uint8.raw\n' > bzip2.nhdr
printf 'Rawfile: blob_8x8x8_uint8.raw\nResolution: 8 8\nFormat: UINT8\n' > two_dims.dat
printf 'Rawfile: blob_8x8x8_uint8.raw\nResolution: 8 8 8\nFormat: FLOAT64\n' > float64.dat
printf 'Rawfile: missing.raw\nResolution: 8 8 8\nFormat: UINT8\n' > no_raw.dat
cp blob_8x8x8_uint8.raw noname.raw
printf 'a,b\n1,2\n2,3\n' > data.csv
printf 'bogus: 1\n' > unknown_key_spec.yaml
printf 'panels: [\n' > unclosed_spec.yaml
printf 'panels:\n  - title: x\n    series:\n      - {file: missing.csv, x: a, y: b, style: line}\n' > no_data_spec.yaml
printf 'panels:\n  - title: x\n    series:\n      - {file: data.csv, x: a, y: c, style: line}\n' > no_column_spec.yaml
printf 'panels:\n  - title: x\n    series:\n      - {file: data.csv, x: a, y: b, style: wiggly}\n' > bad_style_spec.yaml
printf 'panels:\n  - title: x\n    series:\n      - {file: data.csv, x: a, y: b, style: line}\n' > spec.yaml
printf 'panels:\n  - x: {log: true}\n    reference_slopes: [1, 2]\n    series:\n      - {file: data.csv, x: a, y: b}\n' > linear_slopes_spec.yaml
printf 'panels:\n  - x: {log: true}\n    y: {log: true}\n    reference_slopes: [2, zero]\n    series:\n      - {file: data.csv, x: a, y: b}\n' > word_slope_spec.yaml
printf 'panels:\n  - x: {ticks: every}\n    series:\n      - {file: data.csv, x: a, y: b}\n' > bad_ticks_spec.yaml
printf 'panels:\n  - key: under\n    series:\n      - {file: data.csv, x: a, y: b}\n' > bad_key_spec.yaml
printf 'datasets: [\n' > unclosed_catalog.yaml
printf 'bogus: 1\n' > unknown_key_catalog.yaml
mkdir -p exp/tf
cp tf.yaml exp/tf/
cat > exp/good.yaml <<'YAML'
name: good
title: a tiny experiment
paper: {paper: A, item: none, says: nothing}
scenes:
  cube:
    field: linear
    convention: node
    tf: tf/tf.yaml
    camera: {eye: [-8, 4, 0], target: [0, 0, 0], up: [0, 0, 1], fov: 30}
    size: [4, 4]
methods:
  riemann: {rate: 1}
YAML
variant() { sed "$2" exp/good.yaml > "exp/$1.yaml"; }
variant bad_name 's/^name: good/name: Bad Name/'
variant bad_method 's/riemann: {rate: 1}/wobble: {rate: 1}/'
variant bad_rate 's/riemann: {rate: 1}/riemann: {rate: 0}/'
variant no_tf 's|tf/tf.yaml|tf/none.yaml|'
variant bad_convention 's/convention: node/convention: corner/'
variant bad_fov 's/fov: 30/fov: wide/'
variant bad_size 's/size: \[4, 4\]/size: [4]/'
variant bad_eye 's/eye: \[-8, 4, 0\]/eye: [-8, 4]/'
variant unknown_key 's/^title: a tiny experiment/colour: red/'
variant bad_field 's/field: linear/field: wavy/'
{ cat exp/good.yaml; printf 'comparisons:\n  vs: {reference: nobody, thresholds: [0.1]}\n'; } > exp/bad_reference.yaml
{ cat exp/good.yaml; printf 'figures:\n  f: {spec: plots/none.yaml, data: [x.csv]}\n'; } > exp/no_spec.yaml
printf 'name: [\n' > exp/unclosed.yaml
printf -- '- 1\n' > exp/list.yaml

E='^vri-render: error: '
render=("$bin/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 8x8 -o out.exr -q)
bad 64 "${E}The following argument was not expected: --bogus" -- "${render[@]}" --bogus
bad 64 "${E}--tf is required" -- "$bin/vri-render" --volume blob_8x8x8_uint8.raw -o out.exr
bad 64 "${E}Exactly 1 option from \[--volume,--field\] is required \(" -- "$bin/vri-render" --tf tf.yaml -o out.exr
bad 64 "${E}Exactly 1 option from \[--volume,--field\] is required and 2 were given" -- \
    "${render[@]}" --field linear
bad 1 "${E}missing.raw: no such file$" -- "$bin/vri-render" --volume missing.raw --tf tf.yaml -o out.exr
bad 1 "${E}\.: not a regular file$" -- "$bin/vri-render" --volume . --tf tf.yaml -o out.exr
bad 1 "${E}missing.yaml: no such file$" -- "$bin/vri-render" --volume blob_8x8x8_uint8.raw --tf missing.yaml -o out.exr
bad 1 "${E}negative_tau.yaml:2:5: points\[0\] has a negative extinction tau" -- \
    "$bin/vri-render" --volume blob_8x8x8_uint8.raw --tf negative_tau.yaml -o out.exr
bad 1 "${E}unclosed_tf.yaml:2:1: malformed YAML" -- \
    "$bin/vri-render" --volume blob_8x8x8_uint8.raw --tf unclosed_tf.yaml -o out.exr
bad 1 "${E}junk.vdb: .*not a VDB file" -- "$bin/vri-render" --volume junk.vdb --tf tf.yaml -o out.exr
bad 1 "${E}bzip2.nhdr:5: encoding: 'bzip2' is not supported" -- "$bin/vri-render" --volume bzip2.nhdr --tf tf.yaml -o out.exr
bad 1 "${E}float64.dat:3: Format: unknown voxel type 'FLOAT64'" -- \
    "$bin/vri-render" --volume float64.dat --tf tf.yaml -o out.exr
bad 1 "${E}--field: unknown analytic field 'quadratic'" -- "$bin/vri-render" --field quadratic --tf tf.yaml -o out.exr
bad 1 "${E}--method: unknown method 'bogus'" -- "${render[@]}" --method bogus
bad 1 "${E}--placement: unknown placement 'sideways'" -- "${render[@]}" --placement sideways
bad 1 "${E}--precision: unknown precision 'half'" -- "${render[@]}" --precision half
bad 1 "${E}--backend: unknown backend 'metal'" -- "${render[@]}" --backend metal
bad 1 "${E}--convention: unknown grid convention 'corner'" -- "${render[@]}" --convention corner
bad 1 "${E}--accepted-value: unknown accepted value 'median'" -- "${render[@]}" --method coupled --accepted-value median
bad 1 "${E}--interpolation: needs --backend vulkan" -- "${render[@]}" --interpolation sampler
if built_with_vulkan; then
  bad 1 "${E}the Vulkan backend renders in single precision only" -- "${render[@]}" --backend vulkan --precision double
fi
bad 1 "${E}--size: expected a positive image size WIDTHxHEIGHT, got '8by8'" -- \
    "$bin/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml -o out.exr --size 8by8
bad 1 "${E}--size: expected a positive image size WIDTHxHEIGHT, got '0x8'" -- \
    "$bin/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml -o out.exr --size 0x8
bad 1 "${E}--size: an image side is at most 2147483647 pixels, got '2147483648x1'" -- \
    "$bin/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml -o out.exr --size 2147483648x1
bad 1 "${E}--eye: expected three numbers x,y,z, got '1,2'" -- "${render[@]}" --eye 1,2
bad 1 "${E}--eye: expected three numbers x,y,z, got '1,2,nan'" -- "${render[@]}" --eye 1,2,nan
bad 1 "${E}--background: expected three numbers" -- "${render[@]}" --background 1,2
bad 1 "${E}camera up vector 0,0,0 is zero or shorter than" -- "${render[@]}" --up 0,0,0
bad 1 "${E}camera eye and target coincide" -- "${render[@]}" --eye 4,4,4 --target 4,4,4
bad 1 "${E}--fov: expected degrees in \(0, 180\), got 180$" -- "${render[@]}" --fov 180
bad 64 "${E}--fov: expected a number, got 'abc'" -- "${render[@]}" --fov abc
bad 64 "${E}--threads: expected an integer \(decimal, or hexadecimal after 0x\), got 'two'" -- "${render[@]}" --threads two
bad 1 "${E}--threads: expected 0 \(all cores\) or a positive count, got -1" -- "${render[@]}" --threads -1
bad 1 "${E}--repeat: expected a whole number from 1 to 1000, got '0'$" -- "${render[@]}" --repeat 0
bad 1 "${E}--step: expected a number > 0, got '0'$" -- "${render[@]}" --step 0
# An empty value is not a number, as 'abc' is not: a usage error whichever parser sees it first.
bad 64 "${E}--step: expected a number, got '' \(see --help\)$" -- "${render[@]}" --step ''
bad 64 "${E}--repeat: expected an integer \(decimal, or hexadecimal after 0x\), got '' \(see --help\)$" -- "${render[@]}" --repeat ''
bad 64 "^vri-reference: error: --tolerance: expected a number, got '' \(see --help\)$" -- "$bin/vri-reference" --volume blob_8x8x8_uint8.raw \
    --tf tf.yaml --size 8x6 -q -o out.exr --tolerance ''
bad 64 "${E}--step excludes --rate" -- "${render[@]}" --step 0.5 --rate 2
bad 1 "${E}--early-termination: expected a transparency in \[0, 1\), .auto. or .auto:BOUND." -- "${render[@]}" --early-termination 2
bad 1 "${E}--zoom: expected a finite factor >= 1, got 0$" -- "${render[@]}" --zoom 0
bad 1 "${E}sampling rate [0-9.]+e\+(299|300) per voxel \(step 1e-300 voxels\) would put more than 1e9 samples on a ray through this volume$" -- \
  "${render[@]}" --step 1e-300
bad 1 "${E}zoom centre -1,0 is outside the frame \[0, 8\] x \[0, 8\] pixels" -- "${render[@]}" --zoom 2 --zoom-centre -1,0
bad 1 "${E}zoom centre 8.5,4 is outside the frame" -- "${render[@]}" --zoom 2 --zoom-centre 8.5,4
bad 64 "${E}--field-dims excludes --volume" -- "${render[@]}" --field-dims 5,5,5
bad 64 "${E}--field-as-grid excludes --volume" -- "${render[@]}" --field-as-grid
bad 1 "${E}--tolerance: expected a number >= 0, got 'nan'$" -- "${render[@]}" --method coupled --tolerance nan
bad 1 "${E}--h-min: expected a number > 0, got '-1'$" -- "${render[@]}" --method coupled --h-min -1
bad 1 "${E}--h0: expected a number > 0, got '0'$" -- "${render[@]}" --method coupled --h0 0
bad 1 "${E}--h-max: expected a positive number or 'none', got 'zero'" -- "${render[@]}" --method coupled --h-max zero
bad 64 "${E}--log requires --log-ray" -- "${render[@]}" --log ray.csv
bad 1 "${E}the logged pixel 100,100 is outside the 8x8 image" -- \
    "${render[@]}" --method coupled --log-ray 100,100 --log ray.csv
bad 1 "${E}--range: expected lo,hi with hi > lo, got '5,1'" -- "${render[@]}" --range 5,1
bad 1 "${E}--dims and --type go together" -- "${render[@]}" --dims 8,8,8
bad 1 "${E}--dims: expected three positive integers X,Y,Z, got '8,8,8,8'" -- "${render[@]}" --dims 8,8,8,8 --type uint8
bad 1 "${E}--type: unknown voxel type 'int64'" -- "${render[@]}" --dims 8,8,8 --type int64
bad 1 "${E}blob_8x8x8_uint8.raw: file is 512 bytes, expected 576 for 9x8x8 uint8" -- \
    "${render[@]}" --dims 9,8,8 --type uint8
bad 1 "${E}--header-bytes: expected a byte count, got -4" -- "${render[@]}" --dims 8,8,8 --type uint8 --header-bytes -4
bad 1 "${E}--byte-order: expected little or big, got 'middle'" -- "${render[@]}" --byte-order middle
bad 1 "${E}--spacing: expected positive numbers, got '1,0,1'" -- "${render[@]}" --spacing 1,0,1

E='^vri-reference: error: '
reference=("$bin/vri-reference" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 8x8 -o out.exr -q)
bad 64 "${E}--output is required" -- "$bin/vri-reference" --volume blob_8x8x8_uint8.raw --tf tf.yaml
bad 1 "${E}--method: unknown method 'bogus' \(expected exact or riemann\)" -- "${reference[@]}" --method bogus
bad 1 "${E}--step: expected a number > 0, got '0'$" -- "${reference[@]}" --method riemann --step 0
bad 1 "${E}--tolerance: expected a number >= 0, got '-1'$" -- "${reference[@]}" --tolerance -1
bad 1 "${E}--tolerance: must be > 0 for --method exact, got 0$" -- "${reference[@]}" --tolerance 0
bad 1 "${E}--error-image needs --method exact" -- "${reference[@]}" --method riemann --error-image bound.exr
bad 1 "${E}missing.raw: no such file$" -- "$bin/vri-reference" --volume missing.raw --tf tf.yaml -o out.exr
bad 1 "${E}negative_tau.yaml:2:5: points\[0\] has a negative extinction tau" -- \
    "$bin/vri-reference" --volume blob_8x8x8_uint8.raw --tf negative_tau.yaml -o out.exr

E='^vri-tf: error: '
bad 64 "${E}--tf is required" -- "$bin/vri-tf"
bad 64 "${E}--output is required" -- "$bin/vri-tf" --tf tf.yaml
bad 64 "${E}The following argument was not expected: tf.yaml" -- "$bin/vri-tf" tf.yaml tf.yaml -o out.csv
bad 1 "${E}missing.yaml: no such file$" -- "$bin/vri-tf" missing.yaml -o out.csv
bad 1 "${E}\.: is a directory, expected a YAML file$" -- "$bin/vri-tf" . -o out.csv
bad 1 "${E}negative_tau.yaml:2:5: points\[0\] has a negative extinction tau" -- "$bin/vri-tf" negative_tau.yaml -o out.csv
bad 1 "${E}unclosed_tf.yaml:2:1: malformed YAML" -- "$bin/vri-tf" unclosed_tf.yaml -o out.csv
bad 64 "${E}--samples: expected a whole number from 2 to 1000000, got '1'" -- "$bin/vri-tf" tf.yaml --samples 1 -o out.csv
bad 64 "${E}--samples: expected an integer \(decimal, or hexadecimal after 0x\), got 'many'" -- "$bin/vri-tf" tf.yaml --samples many -o out.csv

if built_with_vulkan; then
  E='^vri-sampler-probe: error: '
  bad 64 "${E}The following argument was not expected: --bogus" -- "$bin/vri-sampler-probe" --bogus
  bad 1 "${E}--types: unknown voxel type 'uint32'" -- "$bin/vri-sampler-probe" --types uint32 -o out.csv
fi

E='^vri-diff: error: '
bad 64 "${E}B is required" -- "$bin/vri-diff" a.exr
bad 1 "${E}missing.exr: no such file$" -- "$bin/vri-diff" a.exr missing.exr
bad 1 "${E}junk.exr: cannot read image" -- "$bin/vri-diff" a.exr junk.exr
bad 1 "${E}\.: cannot read image" -- "$bin/vri-diff" . a.exr
bad 4 "${E}images differ in shape: 8x8 with 4 channels vs 4x4 with 4 channels" -- "$bin/vri-diff" a.exr small.exr
bad 64 "${E}--threshold: expected a number >= 0, got '-1'" -- "$bin/vri-diff" a.exr a.exr --threshold -1
bad 64 "${E}--threshold: expected a number, got 'x'" -- "$bin/vri-diff" a.exr a.exr --threshold 0.1,x
# CLI11 would drop an empty item of a comma-separated list (0.1,,0.2 would be two thresholds): refused, in each form.
for list in 0.1,,0.2 0.1, ,0.1 '' '[0.1,,0.2]'; do
    bad 64 "${E}--threshold: an empty item in '$(printf '%s' "$list" | sed 's/[][]/\\&/g')'; expected items separated by single ','" -- \
        "$bin/vri-diff" a.exr a.exr --threshold "$list"
done
bad 64 "${E}--threshold: an empty item in '0\.1,'" -- "$bin/vri-diff" a.exr a.exr --threshold=0.1,
# A list takes one word a use, as typed: the next word is the command's (CLI11 took it for another item, so a
# threshold before the images ate the first image), and brackets are not CLI11's list form.
bad 64 "${E}The following argument was not expected: 0\.2," -- "$bin/vri-diff" a.exr a.exr --threshold 0.1 0.2, --json diff2.json
"$bin/vri-diff" --threshold 0.1 a.exr a.exr --json diff2.json > /dev/null || fail "--threshold before the images refused"
bad 64 "${E}--threshold: expected a number, got '\[0\.1'" -- "$bin/vri-diff" a.exr a.exr --threshold '[0.1,]'
bad 64 "${E}--histogram-range: an empty item in '-1,,1'" -- \
    "$bin/vri-diff" a.exr a.exr --histogram-range -1,,1 --histogram h.csv
# A several-word option takes its least number of words whatever they look like, and a label in brackets as typed.
bad 64 "^vri-tabulate: error: --row: an empty word cannot be one of its values" -- \
    "$bin/vri-tabulate" --layout thresholds --row -O3 '' -o table.md
"$bin/vri-tabulate" --layout thresholds --row '[draft]' diff.json -o bracket.md
grep -q '^| \[draft\] |' bracket.md || fail "--row '[draft]' lost its brackets: $(cat bracket.md)"
bad 64 "^vri-tabulate: error: --cell: expected ROW COLUMN FILE\.\.\., got 2 words \(see --help\)$" -- \
    "$bin/vri-tabulate" --layout matrix --cell A B --value stats.wall_seconds -o table.md
# Nothing after '=' is refused, not read from the next word; a list of a fixed count is given once.
bad 64 "${E}--threshold: nothing after '=' \(give the value after '=' or as the next word\) \(see --help\)$" -- \
    "$bin/vri-diff" a.exr a.exr --threshold= --json diff2.json
bad 64 "^vri-tabulate: error: --row: nothing after '='" -- "$bin/vri-tabulate" --layout thresholds --row= A diff.json -o table.md
bad 64 "${E}--histogram-range: expected 2 numbers separated by ',', once, got '1e-6,1' among 2 uses" -- \
    "$bin/vri-diff" a.exr a.exr --histogram-range 1e-6,1 --histogram-range 1e-3,1 --histogram h.csv
# A list given twice adds up, and replaces the default.
"$bin/vri-diff" a.exr a.exr --threshold 0.1 --threshold 0.2,0.3 --json diff2.json > /dev/null
[[ $(/usr/bin/python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["thresholds"])' diff2.json) == \
   "[0.1, 0.2, 0.3]" ]] || fail "--threshold twice did not add up: $(cat diff2.json)"
bad 64 "^vri-tabulate: error: --thresholds: an empty item in '0\.01,,0\.001'" -- \
    "$bin/vri-tabulate" --layout thresholds --title -- --thresholds 0.01,,0.001 --row A diff.json -o table.md
bad 64 "${E}--histogram-range: an empty item in '1e-6,,1'" -- \
    "$bin/vri-diff" a.exr a.exr --histogram-range 1e-6,,1 --histogram h.csv
"$bin/vri-diff" a.exr a.exr --threshold -0 --json diff2.json > /dev/null || fail "--threshold -0 (a number, not an option) refused"
bad 64 "${E}--failpercent: expected a number from 0 to 100, got '101'" -- "$bin/vri-diff" a.exr a.exr --failpercent 101
bad 64 "${E}--warnpercent: expected a number from 0 to 100, got '-1'" -- "$bin/vri-diff" a.exr a.exr --warnpercent -1
bad 64 "${E}--diff-scale: expected a number > 0, got '0'" -- "$bin/vri-diff" a.exr a.exr --diff-scale 0 --diff-image d.exr
bad 64 "${E}--diff-scale: 1e-320 puts the heat map's top at 1/K, which is not a finite number" -- \
    "$bin/vri-diff" a.exr a.exr --diff-scale 1e-320 --diff-image d.png
bad 64 "${E}--bins-per-decade: expected a number > 0, got '0'" -- \
    "$bin/vri-diff" a.exr a.exr --bins-per-decade 0 --histogram h.csv
bad 64 "${E}--diff-scale requires --diff-image" -- "$bin/vri-diff" a.exr a.exr --diff-scale 2
bad 64 "${E}logarithmic bins need 0 < lo < hi" -- "$bin/vri-diff" a.exr a.exr --histogram-range 1,0.1 --histogram h.csv
bad 64 "${E}--scale-over requires --diff-image" -- "$bin/vri-diff" a.exr a.exr --scale-over a.exr
bad 64 "${E}--diff-scale excludes --scale-over" -- "$bin/vri-diff" a.exr a.exr --diff-image d.png --diff-scale 2 --scale-over a.exr
bad 64 "${E}--scale-over sets the scale of a PNG heat map; --diff-image 'd\.exr' is not a \.png$" -- \
    "$bin/vri-diff" a.exr a.exr --diff-image d.exr --scale-over a.exr
bad 1 "${E}missing\.exr: no such file$" -- "$bin/vri-diff" a.exr a.exr --diff-image d.png --scale-over missing.exr
bad 4 "${E}--scale-over small\.exr: images differ in shape: 8x8 with 4 channels vs 4x4 with 4 channels$" -- \
    "$bin/vri-diff" a.exr a.exr --diff-image d.png --scale-over small.exr
bad 64 "${E}--scale-over excludes --scale-from" -- "$bin/vri-diff" a.exr a.exr --diff-image d.png --scale-from s.json --scale-over a.exr
bad 64 "${E}--scale-from sets the scale of a PNG heat map; --diff-image 'd\.exr' is not a \.png$" -- \
    "$bin/vri-diff" a.exr a.exr --diff-image d.exr --scale-from s.json
echo '{"channels": []}' > noscale.json
bad 1 "${E}--scale-from noscale\.json: .*heat_map" -- "$bin/vri-diff" a.exr a.exr --diff-image d.png --scale-from noscale.json
bad 64 "${E}--diff-image 'a\.png' is the same file as --scale-over 'a\.png'" -- \
    "$bin/vri-diff" a.exr a.exr --diff-image a.png --scale-over a.png

E='^vri-convert: error: '
bad 64 "${E}input is required" -- "$bin/vri-convert"
bad 1 "${E}give an output file, or --info to summarise the input" -- "$bin/vri-convert" blob_8x8x8_uint8.raw
bad 1 "${E}missing.raw: no such file$" -- "$bin/vri-convert" missing.raw out.vdb
bad 1 "${E}flat.nhdr:3: dimension: must be 3" -- "$bin/vri-convert" flat.nhdr --info
bad 1 "${E}bzip2.nhdr:5: encoding: 'bzip2' is not supported \(raw or gzip\)" -- "$bin/vri-convert" bzip2.nhdr out.vdb
bad 1 "${E}two_dims.dat:2: Resolution: expected 3 numbers, got 2" -- "$bin/vri-convert" two_dims.dat --info
bad 1 "${E}float64.dat:3: Format: unknown voxel type 'FLOAT64'" -- "$bin/vri-convert" float64.dat --info
bad 1 "${E}no_raw.dat: Rawfile missing.raw: no such file" -- "$bin/vri-convert" no_raw.dat --info
bad 1 "${E}junk.vdb: .*not a VDB file" -- "$bin/vri-convert" junk.vdb --info
bad 1 "${E}out.xyz: cannot write '.xyz' files" -- "$bin/vri-convert" blob_8x8x8_uint8.raw out.xyz
bad 1 "${E}--grid applies to .vdb input only" -- "$bin/vri-convert" blob_8x8x8_uint8.raw --grid density --info
bad 1 "${E}--dims: expected three positive integers X,Y,Z, got '8,8'" -- \
    "$bin/vri-convert" blob_8x8x8_uint8.raw --dims 8,8 --type uint8 --info
bad 1 "${E}blob_8x8x8_uint8.raw: file is 512 bytes, expected 64 for 4x4x4 uint8" -- \
    "$bin/vri-convert" blob_8x8x8_uint8.raw --dims 4,4,4 --type uint8 --info
bad 1 "${E}--spacing: expected three numbers x,y,z, got '1,1'" -- "$bin/vri-convert" blob_8x8x8_uint8.raw --spacing 1,1 --info
bad 1 "${E}noname.raw: raw file of unknown layout" -- "$bin/vri-convert" noname.raw --info

E='^vri-rays2d: error: '
bad 64 "${E}The following argument was not expected: --bogus" -- "$bin/vri-rays2d" --bogus
bad 1 "${E}nothing to write: give -o" -- "$bin/vri-rays2d"
bad 1 "${E}2D study: at least one ray is needed" -- "$bin/vri-rays2d" --rays 0 -o rays.csv
bad 1 "${E}--convention: unknown grid convention 'corner'" -- "$bin/vri-rays2d" --convention corner -o rays.csv
bad 1 "${E}--placements: unknown placement 'sideways'" -- "$bin/vri-rays2d" --placements eye,sideways -o rays.csv
bad 1 "${E}--rates: expected positive numbers separated by commas, got '1,0'" -- "$bin/vri-rays2d" --rates 1,0 -o rays.csv
bad 1 "${E}--rates: expected positive numbers separated by commas, got '1,,2'" -- \
    "$bin/vri-rays2d" --rates 1,,2 -o rays.csv
bad 1 "${E}--eye: expected two numbers x,y, got '1'" -- "$bin/vri-rays2d" --eye 1 -o rays.csv
bad 1 "${E}2D study: the eye 0.5,0 is inside the square \(or on its border\); it must be outside it" -- \
    "$bin/vri-rays2d" --eye 0.5,0 -o rays.csv
bad 1 "${E}2D study: the field of view must be in \(0, 180\) degrees" -- "$bin/vri-rays2d" --fov 0 -o rays.csv
bad 1 "${E}2D study: the square's side must be positive" -- "$bin/vri-rays2d" --side -3 -o rays.csv
bad 1 "${E}2D study: the grid needs at least 2x2 voxels" -- "$bin/vri-rays2d" --grid 1 -o rays.csv
bad 1 "${E}--diagram-rays: expected indices in 0..119" -- "$bin/vri-rays2d" --diagram-rays 500 --diagram d.csv
bad 1 "${E}--diagram-rate: expected a positive sampling rate" -- "$bin/vri-rays2d" --diagram-rate 0 --diagram d.csv
bad 1 "${E}field image: the resolution must be at least 2, got 1" -- \
    "$bin/vri-rays2d" --field-resolution 1 --field-image f.csv

E='^vri-tabulate: error: '
bad 64 "${E}--layout is required" -- "$bin/vri-tabulate" -o table.md
bad 64 "${E}--layout: pie not in \{thresholds,matrix,tradeoff,convergence\}" -- "$bin/vri-tabulate" --layout pie -o table.md
bad 1 "${E}--layout thresholds needs --row LABEL FILE" -- "$bin/vri-tabulate" --layout thresholds -o table.md
bad 1 "${E}missing.json: no such file$" -- "$bin/vri-tabulate" --layout thresholds --row A missing.json -o table.md
bad 1 "${E}broken.json: not valid JSON" -- "$bin/vri-tabulate" --layout thresholds --row A broken.json -o table.md
bad 1 "${E}stats.json: has no 'thresholds'" -- "$bin/vri-tabulate" --layout thresholds --row A stats.json -o table.md
bad 1 "${E}diff.json: no count above 0.5" -- \
    "$bin/vri-tabulate" --layout thresholds --row A diff.json --thresholds 0.5 -o table.md
bad 64 "${E}--precision: expected a whole number from 0 to 17, got '18'" -- \
    "$bin/vri-tabulate" --layout thresholds --row A diff.json --precision 18 -o table.md
for decimals in 18 99 -1 two 1.0; do  # the same range as --precision, read as every number is
    bad 1 "${E}--column-precision B: expected a whole number from 0 to 17, got '$decimals'$" -- \
        "$bin/vri-tabulate" --layout matrix --cell A B stats.json --value stats.wall_seconds \
        --column-precision B "$decimals" -o table.md
done
# CLI11 takes an empty word for its break between two uses of an option of several words, and would lose it.
bad 64 "${E}--column-precision: an empty word cannot be one of its values \(see --help\)$" -- \
    "$bin/vri-tabulate" --layout matrix --cell A B stats.json --value stats.wall_seconds \
    --column-precision B '' -o table.md
bad 64 "${E}--row: an empty word cannot be one of its values \(see --help\)$" -- \
    "$bin/vri-tabulate" --layout thresholds --row '' diff.json -o table.md
bad 64 "${E}--cell: an empty word cannot be one of its values \(see --help\)$" -- \
    "$bin/vri-tabulate" --layout matrix --cell A '' stats.json --value stats.wall_seconds -o table.md
bad 1 "${E}--layout matrix needs --value EXPR" -- "$bin/vri-tabulate" --layout matrix --cell A B stats.json -o table.md
bad 1 "${E}stats.json: has no 'stats.error_bound'" -- \
    "$bin/vri-tabulate" --layout matrix --cell A B stats.json --value stats.error_bound.max -o table.md
bad 1 "${E}value 'stats.nothing': 'stats.nothing' is no field of a render's stats \\(nearest: stats.nonfinite_pixels\\)" -- \
    "$bin/vri-tabulate" --layout matrix --cell A B stats.json --value stats.nothing -o table.md
bad 1 "${E}value '1/': expected a dotted JSON path" -- \
    "$bin/vri-tabulate" --layout matrix --cell A B stats.json --value 1/ -o table.md
bad 1 "${E}--row belongs to --layout thresholds" -- "$bin/vri-tabulate" --layout tradeoff --row A diff.json -o table.md
bad 1 "${E}--cell belongs to --layout matrix" -- \
    "$bin/vri-tabulate" --layout thresholds --row A diff.json --cell A B stats.json -o table.md
bad 1 "${E}diff.json: no count above 0.7" -- \
    "$bin/vri-tabulate" --layout tradeoff --run a stats.json diff.json --threshold 0.7 -o table.md

E='^vri-plot: error: '
bad 64 "${E}SPEC is required" -- "$bin/vri-plot" -o fig.png
bad 1 "${E}missing.yaml: no such file$" -- "$bin/vri-plot" missing.yaml -o fig.png
bad 1 "${E}unknown_key_spec.yaml:1:1: unknown key 'bogus'" -- "$bin/vri-plot" unknown_key_spec.yaml -o fig.png --script-only
bad 1 "${E}unclosed_spec.yaml:2:1: malformed YAML" -- "$bin/vri-plot" unclosed_spec.yaml -o fig.png --script-only
bad 1 "${E}no_data_spec.yaml:4:16: data file missing.csv does not exist" -- \
    "$bin/vri-plot" no_data_spec.yaml -o fig.png --script-only
bad 1 "${E}no_column_spec.yaml:4:35: column 'c' is not in data.csv \(it has: a, b\)" -- \
    "$bin/vri-plot" no_column_spec.yaml -o fig.png --script-only
bad 1 "${E}bad_style_spec.yaml:4:[0-9]+: panels\[0\].series\[0\].style 'wiggly' is unknown" -- \
    "$bin/vri-plot" bad_style_spec.yaml -o fig.png --script-only
bad 1 "${E}fig.jpg: the figure's name must end in .png" -- "$bin/vri-plot" spec.yaml -o fig.jpg --script-only
bad 1 "${E}linear_slopes_spec.yaml:3:23: panels\[0\].reference_slopes needs log x and y axes" -- \
    "$bin/vri-plot" linear_slopes_spec.yaml -o fig.png --script-only
bad 1 "${E}word_slope_spec.yaml:4:27: panels\[0\].reference_slopes\[1\] must be a number" -- \
    "$bin/vri-plot" word_slope_spec.yaml -o fig.png --script-only
bad 1 "${E}bad_ticks_spec.yaml:2:16: panels\[0\].x.ticks 'every' is unknown \(expected auto or data\)$" -- \
    "$bin/vri-plot" bad_ticks_spec.yaml -o fig.png --script-only
bad 1 "${E}bad_key_spec.yaml:2:10: panels\[0\].key 'under' is unknown \(expected top left, .*, below or off\)$" -- \
    "$bin/vri-plot" bad_key_spec.yaml -o fig.png --script-only
bad 64 "${E}--data-dir: Directory does not exist: missingdir" -- \
    "$bin/vri-plot" spec.yaml -o fig.png --data-dir missingdir --script-only

E='^vri-run: error: '
run=("$bin/vri-run" --dry-run --results results)
bad 1 "${E}nothing to do: name experiment files or --gallery DIR" -- "$bin/vri-run"
bad 1 "${E}VRI_VOXEL_LOADS: expected gather or scalar, got 'bogus'$" -- env VRI_VOXEL_LOADS=bogus "${run[@]}" exp/good.yaml
bad 64 "${E}The following argument was not expected: --bogus" -- "${run[@]}" --bogus exp/good.yaml
bad 1 "${E}--record and --check apply to quick runs \(add --quick\)" -- "${run[@]}" --record exp/good.yaml
bad 64 "${E}--record excludes --check" -- "${run[@]}" --record --check exp/good.yaml
bad 1 "${E}exp/missing.yaml: no such file$" -- "${run[@]}" exp/missing.yaml
bad 1 "${E}exp/unclosed.yaml:2:1: malformed YAML" -- "${run[@]}" exp/unclosed.yaml
bad 1 "${E}exp/list.yaml:1:1: an experiment must be a mapping" -- "${run[@]}" exp/list.yaml
bad 1 "${E}exp/bad_name.yaml:1:7: name must be letters, digits, '.', '_', '\+' or '-'" -- "${run[@]}" exp/bad_name.yaml
bad 1 "${E}exp/unknown_key.yaml:2:1: unknown key 'colour'" -- "${run[@]}" exp/unknown_key.yaml
bad 1 "${E}exp/bad_method.yaml:12:11: methods entry 'wobble' has no method.*unknown method 'wobble'" -- \
    "${run[@]}" exp/bad_method.yaml
bad 1 "${E}exp/bad_rate.yaml:12:19: rate: expected a number > 0, got '0'$" -- "${run[@]}" exp/bad_rate.yaml
bad 1 "${E}exp/no_tf.yaml:8:9: tf: no such file: exp/tf/none.yaml" -- "${run[@]}" exp/no_tf.yaml
bad 1 "${E}exp/bad_convention.yaml:7:17: convention: unknown grid convention 'corner'" -- \
    "${run[@]}" exp/bad_convention.yaml
bad 1 "${E}exp/bad_fov.yaml:9:70: fov must be a number" -- "${run[@]}" exp/bad_fov.yaml
bad 1 "${E}exp/bad_size.yaml:10:11: size must be \[width, height\]" -- "${run[@]}" exp/bad_size.yaml
bad 1 "${E}exp/bad_eye.yaml:9:19: eye must be \[x, y, z\]" -- "${run[@]}" exp/bad_eye.yaml
bad 1 "${E}exp/bad_field.yaml:6:12: unknown analytic field 'wavy'" -- "${run[@]}" exp/bad_field.yaml
bad 1 "${E}exp/bad_reference.yaml:14:19: unknown run 'nobody'" -- "${run[@]}" exp/bad_reference.yaml
bad 1 "${E}exp/no_spec.yaml:14:13: spec: no such file: exp/plots/none.yaml" -- "${run[@]}" exp/no_spec.yaml

E='^vri-data: error: '
bad 64 "${E}The following argument was not expected: --bogus" -- "$bin/vri-data" --bogus
bad 1 "${E}missing.yaml: no such file$" -- "$bin/vri-data" --catalog missing.yaml --data-dir . --no-download
bad 1 "${E}unclosed_catalog.yaml:2:1: malformed YAML" -- \
    "$bin/vri-data" --catalog unclosed_catalog.yaml --data-dir . --no-download
bad 1 "${E}unknown_key_catalog.yaml:1:1: unknown key 'bogus' \(expected one of: datasets\)" -- \
    "$bin/vri-data" --catalog unknown_key_catalog.yaml --data-dir . --no-download
bad 1 "${E}--only: unknown dataset 'nosuch'" -- \
    "$bin/vri-data" --catalog "$VRI_SOURCE/experiments/datasets.yaml" --data-dir . --only nosuch --no-download
bad 64 "${E}--only: an empty item in 'bonsai,,engine'" -- \
    "$bin/vri-data" --catalog "$VRI_SOURCE/experiments/datasets.yaml" --data-dir . --only bonsai,,engine --no-download

bad 64 "^vri-render: error: --list-devices takes no other argument" -- "$bin/vri-render" --list-devices --bogus

bad_done
