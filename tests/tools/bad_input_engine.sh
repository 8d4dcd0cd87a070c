#!/usr/bin/env bash
# Bad input to vri-render --early-termination: one line naming the option, exit 1, nothing written; `auto`
# refused where the Simpson methods cannot bound what an ended ray leaves out.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
source "$(dirname "${BASH_SOURCE[0]}")/lib/bad_input.sh"
bin=${VRI_BIN:?}
source "$(dirname "${BASH_SOURCE[0]}")/lib/blob.sh" && write_blob_scene
scene=(--volume blob_8x8x8_uint8.raw --tf tf.yaml --size 8x6 -q -o out.exr --stats out.json)
expected="expected a transparency in \[0, 1\), 'auto' or 'auto:BOUND' with a bound in \(0, 1\)"

for value in auto:0 auto:1 auto: auto:x soon 1 -0.5 nan; do
  bad 1 "^vri-render: error: --early-termination: $expected, got '$value'$" -- \
    "$bin/vri-render" "${scene[@]}" --early-termination "$value"
done
bad 1 "^vri-render: error: --early-termination: --method exact ends rays by its --tolerance$" -- \
  "$bin/vri-render" "${scene[@]}" --method exact --early-termination auto
# The Simpson methods' bound grows as exp(tau h / 48) (libvri/core/early_termination.h): without an h_max a
# step may cross the whole ray, and at an extinction of 1e4 that leaves double's range.
cat > dense.yaml <<'YAML'
points:
  - [0.0, 1.0, 1.0, 1.0, 1e4]
  - [1.0, 1.0, 1.0, 1.0, 1e4]
YAML
bad 1 "^vri-render: error: --early-termination auto:0.01: decoupled with steps up to the whole ray \(no h_max\) at this transfer function's largest tau cannot bound what an ended ray leaves out \(inf times its transparency\): give --h-max or a transparency threshold$" -- \
  "$bin/vri-render" --volume blob_8x8x8_uint8.raw --tf dense.yaml --size 8x6 -q -o out.exr --method decoupled --h-max none --early-termination auto:0.01
if built_with_vulkan; then
  bad 1 "^vri-render: error: early termination 'auto': the Vulkan backend takes a transparency threshold only$" -- \
    "$bin/vri-render" "${scene[@]}" --backend vulkan --early-termination auto
fi
bad_done
