#!/usr/bin/env bash
# Bad names and paths, each one line naming the file, line, column and key, exit 1, nothing written:
# experiment, scene, method, comparison, command, table and figure names outside the safe set, a table's
# value naming no field of the stats schema,
# command options and inputs that would write outside the experiment's folder, tools that cannot be
# a command's, a folder another vri-run holds, a lock file that is not a regular file, and gnuplot
# failing, leaving a cut-off PNG, or killed, each named by its figure.
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
# refused NAME TEXT WHERE: the experiment NAME.yaml holding TEXT is refused with "NAME.yaml:WHERE" (an
# extended regular expression from its line and column on), before anything is written.
refused() {
  printf '%s\n' "$2" > "$1.yaml"
  bad 1 "^vri-run: error: $1.yaml:$3" -- "$run" --results out "$1.yaml"
}
refused stats_field "name: v
$head
$scene
methods:
  riemann: {placement: eye}
tables:
  t: {group_by: scene, value: timing.median_wall_second}" \
  "9:31: value: 'timing.median_wall_second' is no field of a render's stats \\(nearest: timing.median_wall_seconds\\)"
refused dotdot "name: \"..\"
$head
$commands" \
  '1:7: name must be letters, digits'
refused dot "name: \".\"
$head
$commands" \
  '1:7: name must be letters'
refused quote "name: \"x';system('touch\${IFS}marker');x='\"
$head
$commands" \
  '1:7: name must be letters'
refused slash "name: a/b
$head
$commands" \
  '1:7: name must be letters'
refused figure "name: f
$head
$commands
figures:
  \"x';system('touch\${IFS}marker');x='\": {spec: red.yaml, data: [rays.csv]}" \
  '7:3: figures: a name must be letters'
refused command "name: c
$head
commands:
  ../rays: {tool: vri-rays2d, outputs: {o: rays.csv}}" \
  '5:3: commands: a name must be'
refused scene "name: s
$head
scenes:
  \"a b\": {field: linear, convention: node, tf: red.yaml, size: [8, 8]}
methods:
  riemann: {placement: eye}" \
  '5:3: scenes: a name must be'
refused method "name: m
$head
$scene
methods:
  \"it's\": {method: riemann, placement: eye}" \
  "7:3: methods: a name must be"
refused comparison "name: m
$head
$scene
methods:
  riemann: {placement: [eye, entry]}
comparisons:
  .hidden: {reference: riemann-entry}" \
  "9:3: comparisons: a name must be"
refused table "name: t
$head
$scene
methods:
  riemann: {placement: [eye, entry]}
comparisons:
  vs: {reference: riemann-entry}
tables:
  \"\$(touch marker)\": {comparisons: vs}" \
  "11:3: tables: a name must be"
refused device "name: d
$head
$scene
methods:
  riemann: {placement: eye, backend: vulkan, device: [\"0\", \"../../outside\"]}" \
  "7:12: methods entry 'riemann': a swept value does not fit in a run id"
refused output "name: o
$head
commands:
  rays: {tool: vri-rays2d, outputs: {o: ../outside.csv}}" \
  "5:41: output 'o' must be a file name in the results folder"
refused manifest "name: o
$head
commands:
  rays: {tool: vri-rays2d, outputs: {o: manifest.json}}" \
  "5:41: output 'o' must be a file name .*not manifest.json"
refused option "name: o
$head
commands:
  rays: {tool: vri-rays2d, options: {errors: ../outside.md}, outputs: {o: rays.csv}}" \
  "5:46: option 'errors' writes a file: name it under outputs:"
refused path "name: o
$head
commands:
  rays: {tool: vri-rays2d, options: {rotation: ../../x}, outputs: {o: rays.csv}}" \
  "5:48: option 'rotation' names a file or an option"
refused file "name: o
$head
commands:
  rays: {tool: vri-rays2d, options: {rotation: outside.csv}, outputs: {o: rays.csv}}" \
  "5:48: option 'rotation' names a file"
refused shifted "name: o
$head
commands:
  rays: {tool: vri-rays2d, options: {rotation: -o, rates: x}, outputs: {o: rays.csv}}" \
  "5:48: option 'rotation' names a file or an option"
refused input "name: o
$head
commands:
  tf: {tool: vri-tf, inputs: {o: red.yaml}, outputs: {csv: tf.csv}}" \
  "5:34: input 'o' is an option that writes a file"
refused nested "name: o
$head
commands:
  again: {tool: vri-run, outputs: {o: x.csv}}" \
  "5:17: vri-run cannot be a command's tool"
refused fetch "name: o
$head
commands:
  data: {tool: vri-data, outputs: {o: x.csv}}" \
  "5:16: vri-data cannot be a command's tool"

# A folder another process holds: this shell takes the lock as vri-run would, with its pid in the file.
printf '%s\n' "name: good" "$head" "$commands" > good.yaml
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
# A gnuplot that exits 0 with a cut-off PNG (as on a full disk), and one killed mid-way: stand-ins
# first in PATH, outside the work directory. Called as gnuplot -c SCRIPT PNG SVG.
mkdir -p "$VRI_SCRATCH/cut" "$VRI_SCRATCH/killed"
printf '#!/bin/sh\nprintf "\\211PNG\\r\\n\\032\\n" > "$3"\nprintf "<?xml?><svg></svg>\\n" > "$4"\n' > "$VRI_SCRATCH/cut/gnuplot"
printf '#!/bin/sh\nkill -9 $$\n' > "$VRI_SCRATCH/killed/gnuplot"
chmod +x "$VRI_SCRATCH/cut/gnuplot" "$VRI_SCRATCH/killed/gnuplot"
printf 'series:\n  - {file: negative.csv, x: x, y: y}\n' > line.yaml
bad 1 "^vri-plot: error: figs/cut.png: gnuplot failed: the PNG it wrote is not a complete PNG \\(8 bytes\\)$" -- \
  env PATH="$VRI_SCRATCH/cut:$PATH" "$VRI_BIN/vri-plot" line.yaml -o figs/cut.png
bad 1 "^vri-plot: error: figs/killed.png: gnuplot failed: signal 9$" -- \
  env PATH="$VRI_SCRATCH/killed:$PATH" "$VRI_BIN/vri-plot" line.yaml -o figs/killed.png
[ -z "$(find "$VRI_SCRATCH" -name 'marker*')" ] || fail "a name ran as code"
bad_done
