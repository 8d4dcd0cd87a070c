#!/usr/bin/env bash
# vri-sampler-probe end to end: the CSV of every reading, the Markdown summary with one row per voxel
# type, exact readings at the texel centres, and a bad --types giving one error line. Skipped (77) when
# there is no Vulkan device or the build has no Vulkan backend.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"

built_with_vulkan || { echo "built without the Vulkan backend: skipping"; exit 77; }
"$VRI_BIN/vri-render" --list-devices > /dev/null 2>&1 || { echo "no Vulkan device: skipping"; exit 77; }

"$VRI_BIN/vri-sampler-probe" -o probe.csv --summary probe.md 2> log.txt || fail "probe failed: $(cat log.txt)"
[ "$(head -1 probe.csv)" = "type,format,weight,read,error" ] || fail "bad CSV header: $(head -1 probe.csv)"
# R8 unorm must be filterable on every Vulkan device; each probed type has 4097 readings.
[ "$(grep -c '^uint8,R8 unorm,' probe.csv)" -eq 4097 ] || fail "expected 4097 uint8 readings"
grep -q '^uint8,R8 unorm,0,0,0$' probe.csv || fail "the first texel centre does not read 0"
grep -q '^uint8,R8 unorm,1,1,0$' probe.csv || fail "the second texel centre does not read full scale"
grep -q "^| uint8 (R8 unorm) | [0-9]* |" probe.md || fail "no uint8 row in the summary: $(cat probe.md)"
grep -q "^| float32" probe.md || fail "no float32 row in the summary: $(cat probe.md)"
grep -q "^vri-sampler-probe: uint8 (R8 unorm): max error" log.txt || fail "no summary line on stderr"

"$VRI_BIN/vri-sampler-probe" --types uint16 -q -o - > only.csv
[ "$(grep -vc '^type,' only.csv)" -eq 4097 ] || [ "$(wc -l < only.csv)" -eq 1 ] || fail "--types uint16: $(head -3 only.csv)"

set +e; "$VRI_BIN/vri-sampler-probe" --types uint8,int7 -o bad.csv 2> err.txt; rc=$?; set -e
[ "$rc" -ne 0 ] || fail "expected failure for --types uint8,int7"
[ "$(wc -l < err.txt)" -eq 1 ] || fail "expected one error line: $(cat err.txt)"
grep -q "^vri-sampler-probe: error: --types" err.txt || fail "error does not name --types: $(cat err.txt)"
[ ! -e bad.csv ] || fail "output written despite failure"
echo ok
