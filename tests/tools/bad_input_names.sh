#!/usr/bin/env bash
# Bad names and paths, each one line naming the file, line, column and key, exit 1, nothing written:
# experiment, scene, method, comparison, command, table and figure names outside the safe set,
# command options and inputs that would write outside the experiment's folder, tools that cannot be
# a command's, a folder another vri-run holds, a lock file that is not a regular file, and a gnuplot
# failure named by its figure.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
source "$(dirname "${BASH_SOURCE[0]}")/lib/bad_input.sh"
run=$VRI_BIN/vri-run

cat > red.yaml <<'YAML'
points:
  - [0.0, 0.0, 0.0, 0.0, 0.0]
  - [1.0, 1.0, 0.2, 0.1, 0.8]
YAML
head='title: T
paper: {paper: A, item: Fig. 4, says: a test}'
scene='scenes:
  a: {field: linear, field_dims: [5, 5, 5], convention: node, tf: red.yaml, size: [8, 8]}'
commands='commands:
  rays: {tool: vri-rays2d, outputs: {o: rays.csv}}'
# experiment FILE TEXT: writes the experiment file (the work directory's snapshot then includes it).
experiment() { printf '%s\n' "$2" > "$1"; }

experiment dotdot.yaml "name: \"..\"
$head
$commands"
bad 1 '^vri-run: error: dotdot.yaml:1:7: name must be letters, digits' -- "$run" --dry-run dotdot.yaml
experiment dot.yaml "name: \".\"
$head
$commands"
bad 1 '^vri-run: error: dot.yaml:1:7: name must be letters' -- "$run" --results out dot.yaml
experiment quote.yaml "name: \"x';system('touch\${IFS}marker');x='\"
$head
$commands"
bad 1 '^vri-run: error: quote.yaml:1:7: name must be letters' -- "$run" --results out quote.yaml
experiment slash.yaml "name: a/b
$head
$commands"
bad 1 '^vri-run: error: slash.yaml:1:7: name must be letters' -- "$run" --results out slash.yaml
experiment figure.yaml "name: f
$head
$commands
figures:
  \"x';system('touch\${IFS}marker');x='\": {spec: red.yaml, data: [rays.csv]}"
bad 1 '^vri-run: error: figure.yaml:7:3: figures: a name must be letters' -- "$run" --results out figure.yaml
experiment command.yaml "name: c
$head
commands:
  ../rays: {tool: vri-rays2d, outputs: {o: rays.csv}}"
bad 1 '^vri-run: error: command.yaml:5:3: commands: a name must be' -- "$run" --results out command.yaml
experiment scene.yaml "name: s
$head
scenes:
  \"a b\": {field: linear, convention: node, tf: red.yaml, size: [8, 8]}
methods:
  riemann: {placement: eye}"
bad 1 '^vri-run: error: scene.yaml:5:3: scenes: a name must be' -- "$run" --results out scene.yaml
experiment method.yaml "name: m
$head
$scene
methods:
  \"it's\": {method: riemann, placement: eye}"
bad 1 "^vri-run: error: method.yaml:7:3: methods: a name must be" -- "$run" --results out method.yaml
experiment comparison.yaml "name: m
$head
$scene
methods:
  riemann: {placement: [eye, entry]}
comparisons:
  .hidden: {reference: riemann-entry}"
bad 1 "^vri-run: error: comparison.yaml:9:3: comparisons: a name must be" -- "$run" --results out comparison.yaml
experiment table.yaml "name: t
$head
$scene
methods:
  riemann: {placement: [eye, entry]}
comparisons:
  vs: {reference: riemann-entry}
tables:
  \"\$(touch marker)\": {comparisons: vs}"
bad 1 "^vri-run: error: table.yaml:11:3: tables: a name must be" -- "$run" --results out table.yaml
experiment device.yaml "name: d
$head
$scene
methods:
  riemann: {placement: eye, backend: vulkan, device: [\"0\", \"../../outside\"]}"
bad 1 "^vri-run: error: device.yaml:7:12: methods entry 'riemann': a swept value does not fit in a run id" -- \
  "$run" --results out device.yaml
experiment output.yaml "name: o
$head
commands:
  rays: {tool: vri-rays2d, outputs: {o: ../outside.csv}}"
bad 1 "^vri-run: error: output.yaml:5:41: output 'o' must be a file name in the results folder" -- "$run" --results out output.yaml
experiment manifest.yaml "name: o
$head
commands:
  rays: {tool: vri-rays2d, outputs: {o: manifest.json}}"
bad 1 "^vri-run: error: manifest.yaml:5:41: output 'o' must be a file name .*not manifest.json" -- "$run" --results out manifest.yaml
experiment option.yaml "name: o
$head
commands:
  rays: {tool: vri-rays2d, options: {errors: ../outside.md}, outputs: {o: rays.csv}}"
bad 1 "^vri-run: error: option.yaml:5:46: option 'errors' writes a file: name it under outputs:" -- "$run" --results out option.yaml
experiment path.yaml "name: o
$head
commands:
  rays: {tool: vri-rays2d, options: {rotation: ../../x}, outputs: {o: rays.csv}}"
bad 1 "^vri-run: error: path.yaml:5:48: option 'rotation' names a file or an option" -- "$run" --results out path.yaml
experiment file.yaml "name: o
$head
commands:
  rays: {tool: vri-rays2d, options: {rotation: outside.csv}, outputs: {o: rays.csv}}"
bad 1 "^vri-run: error: file.yaml:5:48: option 'rotation' names a file" -- "$run" --results out file.yaml
experiment shifted.yaml "name: o
$head
commands:
  rays: {tool: vri-rays2d, options: {rotation: -o, rates: x}, outputs: {o: rays.csv}}"
bad 1 "^vri-run: error: shifted.yaml:5:48: option 'rotation' names a file or an option" -- "$run" --results out shifted.yaml
experiment input.yaml "name: o
$head
commands:
  tf: {tool: vri-tf, inputs: {o: red.yaml}, outputs: {csv: tf.csv}}"
bad 1 "^vri-run: error: input.yaml:5:34: input 'o' is an option that writes a file" -- "$run" --results out input.yaml
experiment nested.yaml "name: o
$head
commands:
  again: {tool: vri-run, outputs: {o: x.csv}}"
bad 1 "^vri-run: error: nested.yaml:5:17: vri-run cannot be a command's tool" -- "$run" --results out nested.yaml
experiment fetch.yaml "name: o
$head
commands:
  data: {tool: vri-data, outputs: {o: x.csv}}"
bad 1 "^vri-run: error: fetch.yaml:5:16: vri-data cannot be a command's tool" -- "$run" --results out fetch.yaml

# A folder another process holds: this shell takes the lock as vri-run would, with its pid in the file.
experiment good.yaml "name: good
$head
$commands"
mkdir -p held/good
echo $$ > held/good/.vri-run.lock
exec {lock}< held/good/.vri-run.lock
flock -n "$lock"
bad 1 "^vri-run: error: held/good: in use by another vri-run \\(pid $$: .*bad_input_names.sh\\); wait for it" -- \
  "$run" --results held good.yaml
exec {lock}<&-
mkdir -p fifo/good
mkfifo fifo/good/.vri-run.lock
bad 1 "^vri-run: error: fifo/good/.vri-run.lock: the lock file must be a regular file" -- "$run" --results fifo good.yaml

# gnuplot fails (a log axis with no positive value): one line naming the figure, nothing left.
printf 'x,y\n1,-2\n2,-3\n' > negative.csv
printf 'y: {label: e, log: true}\nseries:\n  - {file: negative.csv, x: x, y: y}\n' > negative.yaml
mkdir -p figs
bad 1 "^vri-plot: error: figs/it's a figure.png: gnuplot failed: .*all points y value undefined" -- \
  "$VRI_BIN/vri-plot" negative.yaml -o "figs/it's a figure.png"
[ -z "$(find "$VRI_SCRATCH" -name 'marker*')" ] || fail "a name ran as code"
bad_done
