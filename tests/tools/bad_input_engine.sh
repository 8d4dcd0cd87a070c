#!/usr/bin/env bash
# Bad input to vri-render --early-termination: one line naming the option, exit 1, nothing written.
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
if built_with_vulkan; then
  bad 1 "^vri-render: error: early termination 'auto': the Vulkan backend takes a transparency threshold only$" -- \
    "$bin/vri-render" "${scene[@]}" --backend vulkan --early-termination auto
fi
bad_done
