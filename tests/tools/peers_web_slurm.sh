#!/usr/bin/env bash
# The web peers (three.js, vtk.js, NiiVue in headless Chromium) as an experiment's outside renderers, on both
# executors: vri-run runs each on the scene card locally and as a Slurm job on a real single-node cluster
# (tests/tools/lib/slurm_cluster.sh), and every image, table and diff is bitwise the same (the adapters are
# deterministic: software WebGL, vtk.js's jitter seeded); each run's record names the renderer and its version.
source "$(dirname "${BASH_SOURCE[0]}")/lib/slurm_cluster.sh"
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
bin=${VRI_BIN:?} src=${VRI_SOURCE:?}
web=$src/tools/peers/web
[ -x /usr/bin/chromium ] || { echo "no /usr/bin/chromium (make deps installs it): skipping"; exit 77; }
command -v node >/dev/null || { echo "no node: skipping"; exit 77; }
[ -d "$web/node_modules/playwright-core" ] || { echo "no $web/node_modules (make deps runs npm ci there): skipping"; exit 77; }
start_slurm_cluster "$PWD/cluster"

source "$(dirname "${BASH_SOURCE[0]}")/lib/peer_scene.sh" && write_peer_scene
cat > exp.yaml <<YAML
name: web
title: The web peers on both executors
paper: {paper: none, item: peers, says: a test}
scenes:
  small: {volume: vol_12x12x12_uint8.raw, convention: cell, tf: tf.yaml, size: [40, 30],
          camera: {eye: [16, 21, -22], target: [6, 6, 6], up: [0, 1, 0], fov: 35}}
renderers:
  threejs: {command: [node, $web/three.mjs, "{card}", "{output}", "{stats}"], image: f32}
  vtkjs: {command: [node, $web/vtkjs.mjs, "{card}", "{output}", "{stats}"], image: f32}
  niivue: {command: [node, $web/niivue.mjs, "{card}", "{output}", "{stats}"], image: f32}
references:
  exact: {method: exact, eps: 1e-8}
methods:
  riemann: {step: 0.5}
  threejs: {renderer: threejs, step: 0.5}
  vtkjs: {renderer: vtkjs, step: 0.5}
  niivue: {renderer: niivue, step: 1}
comparisons:
  vs-exact: {reference: exact}
tables:
  errors: {title: "against the exact reference", comparisons: [vs-exact]}
YAML
"$bin/vri-run" --results local exp.yaml 2> local.txt || { cat local.txt; fail "the local run failed"; }
# A job its node loses or cannot start (a fork failing on a loaded machine) costs a retry; a job the cluster
# never starts (its one node drained) gives up with squeue's reason well before the cluster's watchdog.
"$bin/vri-run" --executor slurm --slurm-poll 0.2 --slurm-bundle 0 --slurm-cpus 1 --slurm-retries 2 --slurm-max-pending 300 \
  --results slurm exp.yaml 2> slurm.txt ||
  { cat slurm.txt; fail "the Slurm run failed"; }
grep -q "steps in Slurm jobs" slurm.txt || { cat slurm.txt; fail "the Slurm run submitted no job"; }
for name in threejs vtkjs niivue; do
  for dir in local slurm; do
    /usr/bin/python3 - "$dir/web/$name.json" "$name" <<'PY' || fail "$dir/web/$name.json: not an outside renderer's record"
import json, sys
r = json.load(open(sys.argv[1]))
assert r["tool"] == "vri-outside" and r["stats"]["backend"] == "outside", r["stats"]
assert r["renderer"]["name"].split()[0] in ("three.js", "vtk.js", "NiiVue") and r["renderer"]["version"][0].isdigit(), r["renderer"]
assert r["timing"]["timed"] == "frame", r["timing"]
PY
  done
  "$bin/vri-diff" "local/web/$name.exr" "slurm/web/$name.exr" --fail 0 > /dev/null || fail "$name: the executors' images differ"
done
cmp local/web/errors.csv slurm/web/errors.csv || fail "the error tables differ between the executors"
grep -q "^| niivue |" local/web/errors.md || fail "the table has no row of the web peers: $(cat local/web/errors.md)"
echo "web peers: three.js, vtk.js and NiiVue ran as experiment runs on both executors, bitwise equal"
