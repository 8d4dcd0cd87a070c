#!/usr/bin/env bash
# Outside renderers in experiments (renderers:, methods with renderer:): vri-run runs the card's example
# renderer through vri-outside beside vri's own Riemann sum, compares it like any run, caches it by its
# command, its executable and the script it names (a changed script runs it again, nothing else), and
# refuses a bad renderer entry in one line with file:line:col.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
bin=${VRI_BIN:?} src=${VRI_SOURCE:?}
python=/usr/bin/python3
"$python" -c 'import numpy' 2> /dev/null || { echo "needs python3-numpy: skipping"; exit 77; }
source "$(dirname "${BASH_SOURCE[0]}")/lib/blob.sh" && write_blob_scene
cp "$src/examples/scene_card/render_from_card.py" card_renderer.py

cat > exp.yaml <<YAML
name: outside
title: The card's example renderer beside vri's Riemann sum
scenes:
  blob: {volume: blob_8x8x8_uint8.raw, tf: tf.yaml, size: [24, 18]}
renderers:
  numpy: {command: [$python, card_renderer.py, "{card}", "{output}"], image: f32}
methods:
  numpy-riemann: {renderer: numpy, precision: double, step: [1, 0.5]}
  riemann: {precision: double, step: [1, 0.5]}
references:
  exact: {eps: 1e-9}
comparisons:
  vs-exact: {reference: exact}
tables:
  speed: {layout: tradeoff, title: "Seconds per frame against error", comparisons: [vs-exact]}
YAML
summary() { grep "vri-run: outside:" "$1"; }
"$bin/vri-run" --results res exp.yaml 2> first.txt || { cat first.txt; fail "the run failed"; }
summary first.txt | grep -q "10 steps, 10 ran, 0 cached" || { cat first.txt; fail "expected 10 steps to run"; }
for h in 1 0.5; do  # the example reproduces vri's Riemann sum from the card: the same image
  "$bin/vri-diff" "res/outside/riemann-h$h.exr" "res/outside/numpy-riemann-h$h.exr" --fail 1e-6 > /dev/null ||
    fail "step $h: the outside run differs from vri's"
done
grep -q '"tool": "vri-outside"' res/outside/numpy-riemann-h1.json
grep -q '"timed": "process"' res/outside/numpy-riemann-h1.json
test -s res/outside/vs-exact-numpy-riemann-h0.5.json
# vri-tabulate takes the outside runs like vri's own: a row each, its family the renderer's name.
grep -q "^numpy-riemann-h0.5,numpy," res/outside/speed.csv || { cat res/outside/speed.csv; fail "no outside row in the table"; }

# Cached: nothing runs. The script changes: its two runs, and their comparisons, run again.
"$bin/vri-run" --results res exp.yaml 2> second.txt
summary second.txt | grep -q "10 steps, 0 ran, 10 cached" || { cat second.txt; fail "expected everything cached"; }
echo "# a changed comment" >> card_renderer.py
"$bin/vri-run" --results res exp.yaml 2> third.txt
summary third.txt | grep -q "10 steps, 5 ran, 5 cached" || { cat third.txt; fail "expected the renderer's runs again"; }

# A bad renderer entry: one line naming file, line and column.
bad_entry() {  # bad_entry PATTERN YAML-LINE-FOR-renderers
  sed "s|^  numpy: .*|$2|" exp.yaml > bad.yaml
  if "$bin/vri-run" --dry-run --results bad bad.yaml > /dev/null 2> err.txt; then fail "accepted: $2"; fi
  [ "$(wc -l < err.txt)" -eq 1 ] || { cat err.txt; fail "expected one line for: $2"; }
  grep -Eq "$1" err.txt || { cat err.txt; fail "expected '$1' for: $2"; }
}
bad_entry 'bad.yaml:[0-9]+:[0-9]+: .*unknown placeholder \{out\}' "  numpy: {command: [$python, x.py, '{out}']}"
bad_entry "bad.yaml:[0-9]+:[0-9]+: renderer 'numpy': no program 'no-such-renderer'" "  numpy: {command: [no-such-renderer, '{card}']}"
bad_entry 'bad.yaml:[0-9]+:[0-9]+: image must be exr, png or f32' "  numpy: {command: [$python], image: tiff}"
bad_entry 'bad.yaml:[0-9]+:[0-9]+: unknown renderer .numpy.' "  other: {command: [$python]}"
bad_entry 'bad.yaml:[0-9]+:[0-9]+: timeout must be seconds > 0, got 0' "  numpy: {command: [$python], timeout: 0}"

# A renderer that never ends is stopped at --timeout (SIGTERM), one that ignores SIGTERM 2 s later (SIGKILL);
# without the limit each would run 60 s and then fail another way, so the message is the check, not the time.
timeout_case() {  # timeout_case PROGRAM ARGS...
  local rc=0
  "$bin/vri-outside" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 8x6 -q -o t.exr --timeout 1 -- "$@" 2> t.txt ||
    rc=$?
  [ "$rc" -eq 1 ] && grep -q "ran past the time limit of 1 s and was stopped (--timeout)" t.txt ||
    fail "--timeout 1 on $*: exit $rc, $(cat t.txt)"
  [ ! -e t.exr ] || fail "--timeout: an image was written"
}
timeout_case /bin/sleep 60
timeout_case "$python" -c 'import signal, time; signal.signal(signal.SIGTERM, signal.SIG_IGN); time.sleep(60)'
echo "outside renderers in experiments: run, compared, cached by their script, refused in one line"
