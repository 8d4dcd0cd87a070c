#!/usr/bin/env bash
# The exit-code table of the README for what CLI11 refuses, on every tool built: an unknown option (or
# the required argument it leaves missing) exits 64 with one line ending "(see --help)". In a build
# without the Vulkan backend (-DVRI_VULKAN=OFF), what needs it says so: exit 1, nothing written.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
source "$(dirname "${BASH_SOURCE[0]}")/lib/bad_input.sh"
source "$(dirname "${BASH_SOURCE[0]}")/lib/blob.sh"

bin="$VRI_BIN"
write_blob_scene

tools=0
for tool in "$bin"/vri-*; do
  name=$(basename "$tool")
  bad 64 "^$name: error: (The following argument was not expected: --bogus|.* is required) \(see --help\)$" -- \
    "$tool" --bogus
  tools=$((tools + 1))
done
[ "$tools" -ge 10 ] || fail "only $tools tools in $bin"

if ! built_with_vulkan; then
  no_vulkan='this build has no Vulkan backend \(configured with -DVRI_VULKAN=OFF\)$'
  bad 1 "^vri-render: error: --backend vulkan: $no_vulkan" -- \
    "$bin/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 8x6 -q -o out.exr --backend vulkan
  bad 1 "^vri-render: error: --list-devices: $no_vulkan" -- "$bin/vri-render" --list-devices
  [ ! -e "$bin/vri-sampler-probe" ] || fail "vri-sampler-probe is built without the Vulkan backend"
fi
bad_done
