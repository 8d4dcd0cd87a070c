#!/usr/bin/env bash
# Bad input to the exact method (vri-render --method exact, vri-reference): one line, exit code, nothing written.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
source "$(dirname "${BASH_SOURCE[0]}")/lib/bad_input.sh"
bin=$VRI_BIN
source "$VRI_SOURCE/tests/tools/lib/blob.sh" && write_blob_scene
cat > huge.yaml <<'YAML'
points:
  - [0.0, 1.0, 1.0, 1.0, 1e307]
  - [1.0, 1.0, 1.0, 1.0, 1e307]
YAML
blob=(--volume blob_8x8x8_uint8.raw --tf tf.yaml --size 8x6 -q -o out.exr --stats out.json)
if built_with_vulkan; then
  bad 1 '^vri-render: error: --method exact: runs on --backend cpu only$' -- "$bin/vri-render" "${blob[@]}" --method exact --backend vulkan
fi
bad 1 '^vri-render: error: --precision: --method exact is double only$' -- "$bin/vri-render" "${blob[@]}" --method exact --precision float
bad 1 '^vri-render: error: --step, --rate: --method exact has no step$' -- "$bin/vri-render" "${blob[@]}" --method exact --step 0.5
bad 1 '^vri-render: error: --early-termination: ' -- "$bin/vri-render" "${blob[@]}" --method exact --early-termination 0.01
bad 1 '^vri-render: error: --tolerance: must be > 0 for --method exact' -- "$bin/vri-render" "${blob[@]}" --method exact --tolerance 0
bad 1 '^vri-render: error: transfer function: extinction 1e\+307 per unit length over a box .* overflows double$' -- \
    "$bin/vri-render" --volume blob_8x8x8_uint8.raw --tf huge.yaml --size 8x6 -q -o out.exr --method exact
bad 1 '^vri-reference: error: transfer function: extinction 1e\+307 per unit length over a box .* overflows double$' -- \
    "$bin/vri-reference" --volume blob_8x8x8_uint8.raw --tf huge.yaml --size 8x6 -q -o out.exr
# Options of other methods are refused, not silently ignored.
bad 1 '^vri-render: error: --h0: applies to --method coupled and decoupled only$' -- "$bin/vri-render" "${blob[@]}" --method exact --h0 0.1
bad 1 '^vri-render: error: --h-min: applies to --method coupled and decoupled only$' -- "$bin/vri-render" "${blob[@]}" --h-min 0.1
bad 1 '^vri-render: error: --placement: --method exact takes no samples to place$' -- "$bin/vri-render" "${blob[@]}" --method exact --placement eye
# --max-error out of reach: the search stops before its tolerance underflows, and names the option; a search
# that cannot get down to the bound from a huge --tolerance says to start lower.
bad 1 '^vri-reference: error: --max-error 5e-324: out of reach: at tolerance 5e-324 the largest per-pixel bound is .*, and the next tolerance would underflow double; ask for a larger error$' -- \
    "$bin/vri-reference" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 8x6 -q -o out.exr --max-error 5e-324
bad 1 '^vri-reference: error: --max-error 0\.001: the largest per-pixel bound is still .* after 8 renders of the image \(last tolerance .*\); ask for a larger error or start from a smaller --tolerance$' -- \
    "$bin/vri-reference" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 8x6 -q -o out.exr --max-error 1e-3 --tolerance 1e300
# Below rounding's floor: the search stops at the second render whose bound does not fall (each costs seconds).
bad 1 '^vri-reference: error: --max-error 1e-15: out of reach: the largest per-pixel bound of the pilot \(the view at a quarter of each side\) stopped following the tolerance: .* at tolerance 1e-15, .* at .* \(rounding sets a floor near it\); ask for a larger error$' -- \
    "$bin/vri-reference" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 128x128 -q -o out.exr --max-error 1e-15
bad 1 '^vri-reference: error: --max-error 1e-15: out of reach: the largest per-pixel bound stopped following the tolerance: .*; ask for a larger error$' -- \
    "$bin/vri-reference" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 16x12 -q -o out.exr --max-error 1e-15
bad_done
