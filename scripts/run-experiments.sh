#!/usr/bin/env bash
# Renders the foundation's end-to-end scenes into results/ (the YAML experiment pipeline replaces this).
set -euo pipefail
bin=${1:?usage: run-experiments.sh BIN_DIR RESULTS_DIR}
out=${2:?usage: run-experiments.sh BIN_DIR RESULTS_DIR}/foundation
data=${VRI_DATA_DIR:?set VRI_DATA_DIR to the directory holding the volumes}
mkdir -p "$out"

# Paper A's linear field on its 5^3 node grid, Entry Exit Align Corner, darker = higher intensity
# (intensities reach about 2, so the preview maps [0, 2] to white..black).
"$bin/vri-render" --field linear --field-dims 5,5,5 --convention node --tf experiments/tf/paper-a-linear.yaml \
  --placement entry-exit-corner --rate 1 --size 500x500 --eye -9,-2.5,3 --target 0,0,0 --up 0,0,1 \
  -o "$out/linear-corner.exr" --png "$out/linear-corner.png" --png-invert --png-exposure 0.5 --stats "$out/linear-corner.json"

# Bonsai, paper B's default step h = 0.5 voxel, 800x600.
"$bin/vri-render" --volume "$data/bonsai_256x256x256_uint8.raw" --tf experiments/tf/bonsai.yaml \
  --size 800x600 --step 0.5 --eye 128,400,-300 --target 128,128,128 \
  -o "$out/bonsai-h0.5.exr" --png "$out/bonsai-h0.5.png" --stats "$out/bonsai-h0.5.json"
