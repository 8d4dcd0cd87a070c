#!/usr/bin/env bash
# Bad input to --simd (vri-render, and vri-reference's exact method): one line naming the option, exit 1, nothing
# written.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
source "$(dirname "${BASH_SOURCE[0]}")/lib/bad_input.sh"
bin=${VRI_BIN:?}
source "$(dirname "${BASH_SOURCE[0]}")/lib/blob.sh" && write_blob_scene
scene=(--volume blob_8x8x8_uint8.raw --tf tf.yaml --size 8x6 -q -o out.exr --stats out.json)

bad 1 "^vri-render: error: --simd: unknown value 'yes' \(expected on, off or a SIMD target this CPU and build have: [A-Z0-9, ]+\)$" -- "$bin/vri-render" "${scene[@]}" --simd yes
bad 1 "^vri-render: error: --simd: unknown value '' \(expected on, off or a SIMD target this CPU and build have: [A-Z0-9, ]+\)$" -- "$bin/vri-render" "${scene[@]}" --simd ''
bad 1 "^vri-render: error: VRI_SIMD_TARGET: 'AVX9000' is not a SIMD target this CPU and build have \([A-Z0-9, ]+\)$" -- env VRI_SIMD_TARGET=AVX9000 "$bin/vri-render" "${scene[@]}" --precision float
# The engine's variables are checked before any work, whether or not this render reads them.
bad 1 "^vri-render: error: VRI_VOXEL_LOADS: expected gather or scalar, got 'bogus'$" -- env VRI_VOXEL_LOADS=bogus "$bin/vri-render" "${scene[@]}" --simd off
bad 1 "^vri-reference: error: VRI_SIMD_TARGET: 'AVX9000' is not a SIMD target this CPU and build have \([A-Z0-9, ]+\)$" -- env VRI_SIMD_TARGET=AVX9000 "$bin/vri-reference" "${scene[@]}"
# A named target where the packets cannot run: a sparse volume, a transfer function past 64 points.
bad 1 "^vri-render: error: --simd SCALAR: the SIMD packets need a dense volume \(not --storage sparse\) .*: leave --simd on$" -- "$bin/vri-render" "${scene[@]}" --precision float --storage sparse --simd SCALAR
bad 1 "^vri-render: error: --simd: unknown value 'avx2;x' \(expected on, off or a SIMD target this CPU and build have: [A-Z0-9, ]+\)$" -- "$bin/vri-render" "${scene[@]}" --simd 'avx2;x'
# The exact method's Gauss rules have no scalar twin; the reference Riemann sum is double, never packets.
bad 1 "^vri-reference: error: --simd off: the exact method's Gauss rules have no scalar twin; name a target \(SCALAR is Highway's one-lane fallback\)$" -- "$bin/vri-reference" "${scene[@]}" --simd off
bad 1 "^vri-render: error: --simd off: the exact method's Gauss rules have no scalar twin; name a target \(SCALAR is Highway's one-lane fallback\)$" -- "$bin/vri-render" "${scene[@]}" --method exact --simd off
bad 1 "^vri-reference: error: --simd applies to --method exact only \(the reference Riemann sum is double\)$" -- "$bin/vri-reference" "${scene[@]}" --method riemann --simd on
# A named target where no packet runs (double, or a method without packets) would be recorded as if it ran.
bad 1 "^vri-render: error: --simd SCALAR: the SIMD packets run float riemann, composite and preintegrated only, not riemann in double$" -- "$bin/vri-render" "${scene[@]}" --simd SCALAR
bad 1 "^vri-render: error: --simd SCALAR: the SIMD packets run float riemann, composite and preintegrated only, not coupled in float$" -- "$bin/vri-render" "${scene[@]}" --method coupled --precision float --simd SCALAR
# Below 1e-10 no Gauss batch runs: a named target would be recorded but never run.
bad 1 "^vri-reference: error: --simd SCALAR: the exact method's SIMD Gauss batches run from --tolerance 1e-10 up; at 1e-13 none runs$" -- "$bin/vri-reference" "${scene[@]}" --simd SCALAR
bad 1 "^vri-render: error: --simd SCALAR: the exact method's SIMD Gauss batches run from --tolerance 1e-10 up; at 1e-11 none runs$" -- "$bin/vri-render" "${scene[@]}" --method exact --tolerance 1e-11 --simd SCALAR
# --max-error with a forced target: the search stops where it would go below the batches' range.
bad 1 "^vri-reference: error: --max-error 1e-11: with --simd SCALAR the tolerance must stay at or above 1e-10, where the SIMD Gauss batches run; the search needs 1e-11: ask for a larger error, or leave --simd out$" -- "$bin/vri-reference" "${scene[@]}" --max-error 1e-11 --simd SCALAR
bad 1 "^vri-render: error: --max-error 1e-09: with --simd SCALAR the tolerance must stay at or above 1e-10, where the SIMD Gauss batches run; the search needs .* after a largest per-pixel bound of .*: ask for a larger error, or leave --simd out$" -- "$bin/vri-render" "${scene[@]}" --method exact --max-error 1e-9 --simd SCALAR
bad 1 "^vri-reference: error: --simd: unknown value 'avx9' \(expected on, off or a SIMD target this CPU and build have: [A-Z0-9, ]+\)$" -- "$bin/vri-reference" "${scene[@]}" --simd avx9
if built_with_vulkan; then
  bad 1 "^vri-render: error: --simd: needs --backend cpu$" -- "$bin/vri-render" "${scene[@]}" --backend vulkan --simd on
fi
bad_done
