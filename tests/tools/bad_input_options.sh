#!/usr/bin/env bash
# Bad render options, as the option table (libvri/core/render_option_table.cpp) checks them: the same
# row's check on vri-render's and vri-reference's command lines and in an experiment file's methods,
# and the rules between options, also applied when an experiment file is read. One line, exit 1,
# nothing written.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
source "$(dirname "${BASH_SOURCE[0]}")/lib/bad_input.sh"
bin=${VRI_BIN:?}
source "$(dirname "${BASH_SOURCE[0]}")/lib/blob.sh" && write_blob_scene
render=("$bin/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 8x6 -q -o out.exr --stats out.json)
reference=("$bin/vri-reference" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 8x6 -q -o out.exr)
E='^vri-render: error: '

# Each row's check, on the command line.
bad 1 "${E}--rate: expected a number > 0, got '-2'$" -- "${render[@]}" --rate -2
bad 1 "${E}--step: expected a number > 0, got 'inf'$" -- "${render[@]}" --step inf
bad 1 "${E}--early-termination: expected a transparency in \[0, 1\), 'auto' or 'auto:BOUND' with a bound in \(0, 1\), got '-0.1'$" -- "${render[@]}" --early-termination -0.1
bad 1 "${E}--warm-up: expected a whole number from 0 to 1000, got '-1'$" -- "${render[@]}" --warm-up -1
bad 1 "${E}--tolerance: expected a number >= 0, got '-1'$" -- "${render[@]}" --method coupled --eps -1
bad 1 "${E}--h-min: expected a number > 0, got '0'$" -- "${render[@]}" --method decoupled --h-min 0
bad 1 "${E}--log-ray: expected two integers|${E}--log-ray: " -- "${render[@]}" --method coupled --log-ray x --log r.csv
bad 1 "${E}--device: needs --backend vulkan$" -- "${render[@]}" --device 0
# Pre-integration and jitter: their rows' ranges and the rules between them.
bad 1 "${E}--preint-size: expected a whole number from 2 to 1024, got '1025'$" -- "${render[@]}" --method preintegrated --preint-size 1025
bad 1 "${E}--preint-order: expected a whole number from 1 to 2, got '3'$" -- "${render[@]}" --method preintegrated --preint-order 3
bad 1 "${E}--preint-size: applies to --method preintegrated only$" -- "${render[@]}" --preint-size 64
bad 1 "${E}--early-termination: not available for --method preintegrated " -- "${render[@]}" --method preintegrated --early-termination 0.01
bad 1 "${E}--seed: needs --jitter$" -- "${render[@]}" --seed 3
bad 1 "${E}--frames: expected a whole number from 1 to 1000, got '0'$" -- "${render[@]}" --jitter --frames 0
bad 1 "${E}--jitter: applies to --method riemann, composite and preintegrated only$" -- "${render[@]}" --method simpson --jitter
bad 1 "^vri-reference: error: --method: unknown method 'coupled' \(expected exact or riemann\)$" -- \
    "${reference[@]}" --method coupled
bad 1 "^vri-reference: error: --tolerance applies to --method exact only$" -- "${reference[@]}" --method riemann --tolerance 1e-6
bad 1 "^vri-reference: error: --repeat: expected a whole number from 1 to 1000, got '0'$" -- "${reference[@]}" --repeat 0
# What the row checks, the library's own checks still follow: h0 within [h_min, h_max].
bad 1 "${E}the initial step h0 must be finite and at least h_min" -- "${render[@]}" --method coupled --h0 0.05
# Options that only one tool takes stay unknown to the other.
bad 64 "^vri-reference: error: The following arguments? (was|were) not expected: .*--placement" -- "${reference[@]}" --placement eye

# The same rows read an experiment file's methods: the value's place, the row's words.
mkdir -p exp/tf && cp tf.yaml exp/tf/tf.yaml
experiment() {  # experiment NAME METHODS-LINE
  cat > "exp/$1.yaml" <<YAML
name: options
title: option checks
paper: {paper: none, item: none, says: nothing}
scenes:
  blob: {field: linear, convention: node, tf: tf/tf.yaml, size: [4, 4]}
methods:
  $2
YAML
}
experiment h0 'coupled: {h0: [0.5, 0]}'
experiment warm 'riemann: {warm_up: -1}'
experiment flagword 'riemann: {simd: maybe, precision: float}'
experiment device 'riemann: {device: 0}'
experiment both 'riemann: {step: 0.5, rate: 2}'
experiment exact 'exact: {method: exact, log_ray: "1,1"}'
experiment clamp 'riemann: {clamp: maybe}'
R='^vri-run: error: '
bad 1 "${R}exp/h0\.yaml:7:23: h0: expected a number > 0, got '0'$" -- "$bin/vri-run" --dry-run exp/h0.yaml
bad 1 "${R}exp/warm\.yaml:7:22: warm_up: expected a whole number from 0 to 1000, got '-1'$" -- "$bin/vri-run" --dry-run exp/warm.yaml
bad 1 "${R}exp/flagword\.yaml:7:19: simd: unknown value 'maybe' \(expected on, off or a SIMD target this CPU and build have: [A-Z0-9, ]+\)$" -- "$bin/vri-run" --dry-run exp/flagword.yaml
bad 1 "${R}exp/device\.yaml:7:12: methods entry 'riemann': --device: needs --backend vulkan$" -- \
    "$bin/vri-run" --dry-run exp/device.yaml
bad 1 "${R}exp/both\.yaml:7:12: methods entry 'riemann': --rate: cannot be given with --step$" -- \
    "$bin/vri-run" --dry-run exp/both.yaml
bad 1 "${R}exp/exact\.yaml:7:10: log_ray does not apply to method exact \(vri-reference\)$" -- \
    "$bin/vri-run" --dry-run exp/exact.yaml
bad 1 "${R}exp/clamp\.yaml:7:20: clamp: expected true or false, got 'maybe'$" -- "$bin/vri-run" --dry-run exp/clamp.yaml
bad_done
