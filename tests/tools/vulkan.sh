#!/usr/bin/env bash
# vri-render's Vulkan backend end to end: --list-devices, a render of a tiny volume compared with the
# CPU in float, the stats naming the device, a repeat that reuses the uploaded volume, the hardware
# sampler's interpolation, jittered sampling, pre-integrated classification, and bad --device/--backend/--precision/--interpolation giving one error line. Skipped (77) when there is no Vulkan device or the build has no Vulkan backend.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"

built_with_vulkan || { echo "built without the Vulkan backend: skipping"; exit 77; }
"$VRI_BIN/vri-render" --list-devices > devices.txt 2> /dev/null || { echo "no Vulkan device: skipping"; exit 77; }
# One line per device: index, name, type and API version, tab separated.
awk -F'\t' 'NF != 4 || $1 != NR - 1 { exit 1 }' devices.txt || fail "bad --list-devices output: $(cat devices.txt)"
device=$(head -1 devices.txt | cut -f2)

source "$(dirname "${BASH_SOURCE[0]}")/lib/blob.sh" && write_blob_scene
render() { "$VRI_BIN/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 40x30 --eye 20,14,-9 -q "$@"; }

# Riemann at each placement: within float rounding of the CPU (see tests/unit/vulkan_test.cpp).
for placement in eye entry entry-exit entry-exit-corner; do
  render --placement $placement --step 0.3 --precision float -o cpu-$placement.exr
  render --placement $placement --step 0.3 --backend vulkan --device 0 -o vk-$placement.exr --stats vk-$placement.json
  "$VRI_BIN/vri-diff" cpu-$placement.exr vk-$placement.exr --fail 2e-5 --warn 2e-5 > diff.txt \
    || fail "$placement: Vulkan differs from the CPU: $(cat diff.txt)"
done
# Jittered Riemann at each placement (the same hash of pixel and seed as the CPU's: the same first sample on
# every ray) and the mean of 4 jittered frames: within float rounding of the CPU; a jittered image differs
# from the unjittered one and from another seed's.
for placement in eye entry entry-exit entry-exit-corner; do
  render --placement $placement --step 0.3 --precision float --jitter --seed 11 -o cpu-jitter-$placement.exr
  render --placement $placement --step 0.3 --backend vulkan --jitter --seed 11 -o vk-jitter-$placement.exr
  "$VRI_BIN/vri-diff" cpu-jitter-$placement.exr vk-jitter-$placement.exr --fail 2e-5 --warn 2e-5 > diff.txt \
    || fail "$placement, jittered: Vulkan differs from the CPU: $(cat diff.txt)"
done
render --step 0.3 --precision float --jitter --seed 11 --frames 4 -o cpu-frames.exr
render --step 0.3 --backend vulkan --jitter --seed 11 --frames 4 -o vk-frames.exr --stats vk-frames.json
"$VRI_BIN/vri-diff" cpu-frames.exr vk-frames.exr --fail 2e-5 --warn 2e-5 > diff.txt ||
  fail "4 jittered frames: Vulkan differs from the CPU: $(cat diff.txt)"
grep -q '"frames": 4' vk-frames.json || fail "the stats do not record 4 frames: $(grep -A3 '"jitter"' vk-frames.json)"
render --step 0.3 --backend vulkan --jitter --seed 12 -o vk-jitter-seed12.exr
for other in vk-entry.exr vk-jitter-seed12.exr; do
  ! "$VRI_BIN/vri-diff" vk-jitter-entry.exr $other --fail 1e-3 > /dev/null || fail "vk-jitter-entry.exr equals $other"
done
# Pre-integrated classification, orders 1 and 2, at two placements and jittered, with the TF's colour as
# emission too: the CPU's table looked up as the CPU's float path does, within float rounding of the CPU.
printf 'emission: color\npoints:\n  - [0.0, 0, 0, 0, 0]\n  - [0.3, 1, 0.5, 0.2, 0]\n  - [0.3, 1, 0.5, 0.2, 4]\n  - [0.6, 0.2, 0.4, 1, 1]\n  - [1.0, 1, 1, 1, 2]\n' > colour.yaml
render_tf() { local tf=$1; shift; "$VRI_BIN/vri-render" --volume blob_8x8x8_uint8.raw --tf "$tf" --size 40x30 --eye 20,14,-9 -q "$@"; }
for order in 1 2; do
  for variant in "--placement eye" "--placement entry-exit-corner" "--jitter --seed 5" "colour"; do
    name=preint-o$order-$(tr -dc 'a-z0-9' <<< "$variant")
    tf=tf.yaml
    if [ "$variant" = colour ]; then tf=colour.yaml variant=; fi
    render_tf $tf --method preintegrated --preint-order $order --preint-size 64 --step 0.7 $variant --precision float -o cpu-$name.exr
    render_tf $tf --method preintegrated --preint-order $order --preint-size 64 --step 0.7 $variant --backend vulkan \
      -o vk-$name.exr --stats vk-$name.json
    "$VRI_BIN/vri-diff" cpu-$name.exr vk-$name.exr --fail 2e-5 --warn 2e-5 > diff.txt \
      || fail "pre-integration, order $order, $variant: Vulkan differs from the CPU: $(cat diff.txt)"
    grep -q "\"order\": $order" vk-$name.json && grep -q '"table_error_colour"' vk-$name.json ||
      fail "the Vulkan stats lack the table of order $order: $(grep -A7 '"preintegration"' vk-$name.json)"
  done
done
! "$VRI_BIN/vri-diff" vk-preint-o1-placementeye.exr vk-entry.exr --fail 1e-3 > /dev/null || fail "pre-integration equals Riemann"
grep -q '"backend": "vulkan"' vk-entry.json || fail "stats do not name the backend"
grep -qF "\"device\": \"$device\"" vk-entry.json || fail "stats do not name the device $device"
grep -q '"precision": "float"' vk-entry.json || fail "the Vulkan render is not recorded as float"

# Coupled, by a part of the device's name, repeated on the uploaded volume: within a few tolerances.
render --method coupled --tolerance 0.001 --precision float -o cpu-coupled.exr
render --method coupled --tolerance 0.001 --backend vulkan --device "${device:0:4}" --repeat 3 -o vk-coupled.exr \
  --stats vk-coupled.json
"$VRI_BIN/vri-diff" cpu-coupled.exr vk-coupled.exr --fail 0.004 --warn 0.004 > diff.txt \
  || fail "coupled: Vulkan differs from the CPU: $(cat diff.txt)"
grep -q '"repeats": 3' vk-coupled.json && grep -q '"outer_steps"' vk-coupled.json

# The texture unit's interpolation: the same image up to the sampler's weights (R8 unorm here; lavapipe's
# differ by a few 1e-3, see tests/unit/vulkan_test.cpp), and the stats saying which interpolation ran.
render --step 0.3 --backend vulkan --interpolation sampler -o vk-sampler.exr --stats vk-sampler.json
"$VRI_BIN/vri-diff" vk-entry.exr vk-sampler.exr --fail 0.1 --warn 0.1 > diff.txt \
  || fail "sampler: differs from the shader's interpolation: $(cat diff.txt)"
grep -q '"interpolation": "sampler"' vk-sampler.json || fail "stats do not name the sampler"
grep -q '"interpolation": "shader"' vk-entry.json || fail "stats do not name the shader's interpolation"

expect_error() {  # expect_error PATTERN ARGS...
  local pattern=$1; shift
  set +e; render "$@" -o bad.exr 2> err.txt; local rc=$?; set -e
  [ "$rc" -ne 0 ] || fail "expected failure for: $*"
  [ "$(wc -l < err.txt)" -eq 1 ] || fail "expected one line for: $*: $(cat err.txt)"
  grep -q "^vri-render: error: .*$pattern" err.txt || fail "expected '$pattern' for: $*: $(cat err.txt)"
  if ls bad.* > /dev/null 2>&1; then fail "output written despite failure: $*"; fi
}
expect_error "no Vulkan device matches" --backend vulkan --device no-such-gpu
expect_error "no Vulkan device matches" --backend vulkan --device 99
expect_error "single precision" --backend vulkan --precision double
expect_error "unknown backend" --backend opencl
expect_error "needs --backend vulkan" --device 0
expect_error "needs --backend vulkan" --interpolation sampler
expect_error "unknown interpolation 'nearest'" --backend vulkan --interpolation nearest
echo ok
