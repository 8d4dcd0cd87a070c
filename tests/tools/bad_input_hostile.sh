#!/usr/bin/env bash
# Hostile input (issue 29 items 1, 2, 3, 6, 9, 10): YAML that once hung every reader, frame counts
# without a bound, text inputs without an end, ranges whose width overflows, and two experiments that
# would share a folder. Each case: the exit code, the one stderr line and an unchanged work directory
# (lib/bad_input.sh). A case that hangs again fails on `timeout 10` (exit 124) instead of stalling ctest.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
source "$(dirname "${BASH_SOURCE[0]}")/lib/bad_input.sh"
source "$(dirname "${BASH_SOURCE[0]}")/lib/blob.sh"

bin=$VRI_BIN
t=(timeout 10)  # an array, not a function: each case runs under GNU time (lib/bad_input.sh)

# --- inputs, made before the cases: the work directory must stay as it is from here on ---
write_blob_scene
{
  echo 'name: small'
  echo 'title: One render'
  echo 'paper: {paper: none, item: test, says: a test}'
  echo 'scenes: {red: {field: linear, field_dims: [5, 5, 5], convention: node, tf: tf.yaml, size: [8, 6]}}'
  echo 'methods: {riemann: {rate: 1}}'
} > exp.yaml
cp exp.yaml twin.yaml
sed 's/riemann: {rate: 1}/riemann: {rate: 1, repeat: 1001}/' exp.yaml > repeat.yaml
sed 's/riemann: {rate: 1}/riemann: {rate: 1, warm_up: [1, 100000]}/' exp.yaml > warm.yaml
sed 's/riemann: {rate: 1}/riemann: {rate: 1, jitter: true, frames: 100, repeat: [3, 200]}/' exp.yaml > frames.yaml
sed 's|tf: tf.yaml|tf: /dev/zero|' exp.yaml > devzero.yaml
printf 'name: small\ntitle: \xff\xfe\n' > latin.yaml && sed -n '3,$p' exp.yaml >> latin.yaml
{ cat exp.yaml; printf -- '---\n]\n'; } > exp-bracket.yaml
printf '{"name": "small", "title": "One render"},\n' > exp-comma.json.yaml
printf 'a: 1\n,\n' > block-comma.yaml
printf '{a: 1},' > flow-comma.yaml
printf '[1],\n' > seq-comma.yaml
printf -- '- 1\n,\n' > item-comma.yaml
printf 'points:\n  - [0, 0, 0, 0, 0]\n  - [1, 1, 1, 1, 1]\n]\n' > tf-bracket.yaml
printf 'points: [[0, 0, 0, 0, 0], [1, 1, 1, 1, 1]]\n---\n}\n' > tf-brace.yaml
printf 'points:\n  - [-1e308, 0, 0, 0, 0]\n  - [1e308, 1, 1, 1, 1]\n' > tf-wide.yaml
printf 'NRRD0004\ntype: uint8\ndimension: 3\nsizes: 8 8 8\nencoding: raw\ndata file: blob_8x8x8_uint8.raw\nvri_range:=-1e308 1e308\n' > wide.nhdr
# Item 2: transfer functions past 10,000 points, and YAML past 200,000 nodes, block and flow.
/usr/bin/python3 - <<'PY'
with open("tf-points.yaml", "w") as f:
    f.write("points:\n" + "".join(f"  - [{i / 10000:.6f}, 0.5, 0.5, 0.5, {i % 7 / 10}]\n" for i in range(10001)))
with open("tf-nodes.yaml", "w") as f:
    f.write("points: [" + ", ".join("[0.5, 0, 0, 0, 0]" for _ in range(40000)) + "]\n")
with open("exp-nodes.yaml", "w") as f:
    f.write("name: big\nmethods:\n" + "".join(f"  m{i}: {{step: [0.5, 0.25, 0.125]}}\n" for i in range(60000)))
PY
mkfifo fifo
/usr/bin/python3 -c 'import socket, sys; socket.socket(socket.AF_UNIX).bind(sys.argv[1])' sock
# 64 MiB + 1 byte, sparse, outside the work directory (the harness hashes every file in it).
big=$VRI_SCRATCH/big.yaml
truncate -s $((64 * 1024 * 1024 + 1)) "$big"

# --- item 1: a ',' (or ']', '}') outside a flow collection, in every tool that reads YAML ---
E='^vri-tf: error: '
# After a block mapping, and a ']' or '}' anywhere, yaml-cpp refuses it itself; a ',' elsewhere looped.
bad 1 "${E}block-comma\.yaml:2:1: malformed YAML: end of map not found$" -- "${t[@]}" "$bin/vri-tf" block-comma.yaml -o out.csv
bad 1 "${E}flow-comma\.yaml:1:7: malformed YAML: ',' outside a flow collection$" -- "${t[@]}" "$bin/vri-tf" flow-comma.yaml -o out.csv
bad 1 "${E}seq-comma\.yaml:1:4: malformed YAML: ','" -- "${t[@]}" "$bin/vri-tf" seq-comma.yaml -o out.csv
bad 1 "${E}item-comma\.yaml:2:1: malformed YAML: ','" -- "${t[@]}" "$bin/vri-tf" item-comma.yaml -o out.csv
bad 1 "${E}tf-bracket\.yaml:4:1: malformed YAML: illegal flow end$" -- "${t[@]}" "$bin/vri-tf" tf-bracket.yaml -o out.csv
bad 1 "${E}tf-brace\.yaml:3:1: malformed YAML: illegal flow end$" -- "${t[@]}" "$bin/vri-tf" tf-brace.yaml -o out.csv
bad 1 "^vri-run: error: exp-bracket\.yaml:7:1: malformed YAML: illegal flow end$" -- "${t[@]}" "$bin/vri-run" --dry-run exp-bracket.yaml
bad 1 "^vri-run: error: exp-comma\.json\.yaml:1:41: malformed YAML: ','" -- "${t[@]}" "$bin/vri-run" --results out exp-comma.json.yaml
bad 1 "^vri-plot: error: flow-comma\.yaml:1:7: malformed YAML: ','" -- "${t[@]}" "$bin/vri-plot" flow-comma.yaml -o fig.png
bad 1 "^vri-data: error: item-comma\.yaml:2:1: malformed YAML: ','" -- "${t[@]}" "$bin/vri-data" --catalog item-comma.yaml --data-dir .
bad 1 "^vri-render: error: flow-comma\.yaml:1:7: malformed YAML: ','" -- "${t[@]}" "$bin/vri-render" --field linear --tf flow-comma.yaml -q -o out.exr
bad 1 "^vri-reference: error: seq-comma\.yaml:1:4: malformed YAML: ','" -- "${t[@]}" "$bin/vri-reference" --field linear --tf seq-comma.yaml -q -o out.exr

# --- item 2: a bounded transfer function, refused on the event stream before yaml-cpp builds its tree ---
bad 1 "${E}tf-points\.yaml:2:3: 'points' has 10001 points, more than the limit of 10000$" -- "${t[@]}" "$bin/vri-tf" tf-points.yaml -o out.csv
bad 1 "${E}tf-nodes\.yaml:1:[0-9]+: more than 200000 YAML nodes \(the limit of a vri YAML file\)$" -- "${t[@]}" "$bin/vri-tf" tf-nodes.yaml -o out.csv
bad 1 "^vri-render: error: tf-nodes\.yaml:1:[0-9]+: more than 200000 YAML nodes" -- "${t[@]}" "$bin/vri-render" --field linear --tf tf-nodes.yaml -q -o out.exr
bad 1 "^vri-run: error: exp-nodes\.yaml:[0-9]+:[0-9]+: more than 200000 YAML nodes" -- "${t[@]}" "$bin/vri-run" --dry-run exp-nodes.yaml

# --- item 3: frame counts within 1000, on the command line and in experiment files ---
bad 1 "^vri-render: error: --repeat: expected a whole number from 1 to 1000, got '1001'$" -- \
  "$bin/vri-render" --field linear --tf tf.yaml -q -o out.exr --repeat 1001
bad 1 "^vri-render: error: --warm-up: expected a whole number from 0 to 1000, got '1001'$" -- \
  "$bin/vri-render" --field linear --tf tf.yaml -q -o out.exr --warm-up 1001
bad 64 "^vri-render: error: --warm-up: 2147483648 is outside the range of this integer option" -- \
  "$bin/vri-render" --field linear --tf tf.yaml -q -o out.exr --warm-up 2147483648
bad 1 "^vri-reference: error: --repeat: expected a whole number from 1 to 1000" -- \
  "$bin/vri-reference" --field linear --tf tf.yaml -q -o out.exr --repeat 100000
bad 1 "^vri-run: error: repeat\.yaml:5:[0-9]+: .*repeat.*expected a whole number from 1 to 1000, got '1001'$" -- "$bin/vri-run" --dry-run repeat.yaml
bad 1 "^vri-run: error: warm\.yaml:5:[0-9]+: .*warm_up.*expected a whole number from 0 to 1000, got '100000'$" -- "$bin/vri-run" --dry-run warm.yaml

# --- item 6: text inputs within 64 MiB, checked while reading; what is not a regular file named so ---
limit="more than 67108864 bytes, the limit for a YAML file"
bad 1 "^vri-tf: error: /dev/zero: not a regular file, $limit$" -- "${t[@]}" "$bin/vri-tf" /dev/zero -o out.csv
bad 1 "^vri-render: error: /dev/zero: not a regular file, $limit$" -- "${t[@]}" "$bin/vri-render" --field linear --tf /dev/zero -q -o out.exr
bad 1 "^vri-run: error: /dev/zero: not a regular file, $limit$" -- "${t[@]}" "$bin/vri-run" --dry-run /dev/zero
bad 1 "^vri-plot: error: /dev/zero: not a regular file, $limit$" -- "${t[@]}" "$bin/vri-plot" /dev/zero -o fig.png
bad 1 "^vri-data: error: /dev/zero: not a regular file, $limit$" -- "${t[@]}" "$bin/vri-data" --catalog /dev/zero --data-dir .
bad 1 "^vri-tabulate: error: /dev/zero: not a regular file, more than 67108864 bytes, the limit for a JSON file$" -- \
  "${t[@]}" "$bin/vri-tabulate" --layout thresholds --row a /dev/zero -o table.md
bad 1 "^vri-tf: error: .*/big\.yaml: $limit$" -- "${t[@]}" "$bin/vri-tf" "$big" -o out.csv
# A FIFO whose writer never stops, as --tf <(yes) would be.
bad 1 "^vri-tf: error: fifo: not a regular file, $limit$" -- "${t[@]}" bash -c 'yes "a: 1" > fifo & exec "$0" fifo -o out.csv' "$bin/vri-tf"
bad 1 "^vri-tf: error: sock: not a regular file, expected a YAML file$" -- "${t[@]}" "$bin/vri-tf" sock -o out.csv

# --- item 9: ranges whose width overflows a double ---
bad 1 "^vri-render: error: --range: hi - lo must be at most the largest double .*got '-1e308,1e308'$" -- \
  "$bin/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml -q -o out.exr --range=-1e308,1e308
bad 1 "^vri-reference: error: --range: hi - lo must be at most the largest double" -- \
  "$bin/vri-reference" --volume blob_8x8x8_uint8.raw --tf tf.yaml -q -o out.exr --range=-1.7e308,1.7e308
bad 1 "^vri-render: error: --range: expected lo,hi with hi > lo, got '-1e309,1'$" -- \
  "$bin/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml -q -o out.exr --range=-1e309,1
bad 1 "^vri-tf: error: tf-wide\.yaml: the points' s from -1e\+308 to 1e\+308 span more than the largest double" -- \
  "$bin/vri-tf" tf-wide.yaml -o out.csv
bad 1 "^vri-render: error: tf-wide\.yaml: the points' s from" -- "$bin/vri-render" --field linear --tf tf-wide.yaml -q -o out.exr
bad 1 "^vri-convert: error: wide\.nhdr: value range -1e\+308 1e\+308: expected finite lo < hi with a finite hi - lo$" -- \
  "$bin/vri-convert" --info wide.nhdr

# --- item 10: two experiments of one name in one vri-run ---
bad 1 "^vri-run: error: twin\.yaml: name 'small' is also exp\.yaml's \(both would write out/small/\)$" -- \
  "$bin/vri-run" --results out exp.yaml twin.yaml
bad 1 "^vri-run: error: twin\.yaml: name 'small' is also exp\.yaml's \(both would write build/experiments-quick/small/\)$" -- \
  "$bin/vri-run" --quick --dry-run exp.yaml twin.yaml
bad 1 "^vri-run: error: exp\.yaml: name 'small' is also exp\.yaml's" -- "$bin/vri-run" --dry-run --results out exp.yaml exp.yaml

# Limits that hold one by one but not together (issue 48, class 4): frames x (warm-up + repeat).
bad 1 "^vri-render: error: --warm-up 1000 \+ --repeat 1000 x --frames 1000 asks for 1001000 frames; at most 10000 in one run$" -- \
  "${t[@]}" "$bin/vri-render" --field linear --tf tf.yaml --jitter --frames 1000 --repeat 1000 --warm-up 1000 -q -o out.exr
bad 1 "^vri-run: error: frames\.yaml:[0-9]+:[0-9]+: .*--warm-up 0 \+ --repeat 200 x --frames 100 asks for 20000 frames; at most 10000 in one run$" -- \
  "${t[@]}" "$bin/vri-run" --dry-run frames.yaml

# Messages that say what was wrong (issue 48, class 9): a transfer function that exists but is no file; a
# title that is not UTF-8, refused at its line rather than after every step ran (the manifest is JSON).
bad 1 "^vri-run: error: devzero\.yaml:4:[0-9]+: tf: /dev/zero is not a regular file$" -- "$bin/vri-run" --dry-run devzero.yaml
bad 1 "^vri-run: error: latin\.yaml:2:8: title: not UTF-8 at byte 0 \('\\\\xFF\\\\xFE'\)$" -- "$bin/vri-run" --dry-run latin.yaml

# A '%' in the results path, which Slurm would read as a pattern in the jobs' --chdir (issue 48, class 3a).
bad 1 "^vri-run: error: --executor slurm: the results folder .*/r%j/small holds a '%', which Slurm reads as a pattern" -- \
  "$bin/vri-run" --executor slurm --results 'r%j' exp.yaml

bad_done
