#!/usr/bin/env bash
# Values outside [0, 1]: every render's stats count them (out_of_range_pixels), for each method and
# both tools; an opaque transfer function with a long Riemann step overshoots, a faint one does not.
set -euo pipefail
bin=${VRI_BIN:?} dir=${VRI_SCRATCH:?}
rm -rf "$dir" && mkdir -p "$dir" && cd "$dir"
fail() { echo "FAIL: $*" >&2; exit 1; }
source "$(dirname "${BASH_SOURCE[0]}")/lib/blob.sh" && write_blob_scene
cat > dense.yaml <<'YAML'
points:
  - [0.0, 1.0, 1.0, 1.0, 20.0]
  - [1.0, 1.0, 1.0, 1.0, 20.0]
YAML
scene=(--volume blob_8x8x8_uint8.raw --size 16x12 -q)
field() { jq -r ".stats.out_of_range_pixels.$2" "$1"; }

# tau * h = 20 * 2: each Riemann term tau * h * T is far above the 1 - exp(-tau * h) it stands for.
"$bin/vri-render" "${scene[@]}" --tf dense.yaml --step 2 -o dense.exr --stats dense.json
[ "$(field dense.json pixels)" -gt 0 ] || fail "an overshooting Riemann sum counts no pixel out of range"
awk -v m="$(field dense.json max)" 'BEGIN { exit !(m > 1) }' || fail "largest value $(field dense.json max) is not above 1"
[ "$(field dense.json channels_above_1)" -ge "$(field dense.json pixels)" ] || fail "fewer channels above 1 than pixels"
[ "$(field dense.json channels_below_0)" -eq 0 ] || fail "a render with values below 0"
# The same scene at a short step, and the exact method: within [0, 1].
"$bin/vri-render" "${scene[@]}" --tf tf.yaml --step 0.25 -o faint.exr --stats faint.json
[ "$(field faint.json pixels)" -eq 0 ] || fail "a faint render has $(field faint.json pixels) pixels out of range"
"$bin/vri-reference" "${scene[@]}" --tf dense.yaml -o exact.exr --stats exact.json
[ "$(field exact.json pixels)" -eq 0 ] || fail "the exact reference has pixels out of range"
awk -v m="$(field exact.json max)" 'BEGIN { exit !(m <= 1 && m > 0.9) }' || fail "exact max $(field exact.json max)"
for method in simpson coupled decoupled; do
  "$bin/vri-render" "${scene[@]}" --tf dense.yaml --method $method -o m.exr --stats m.json
  [ "$(field m.json pixels)" != null ] || fail "$method: no out_of_range_pixels in the stats"
done
grep -q '"clamp": false' dense.json || fail "the settings do not say clamp: false"

# --clamp: the image clamped to [0, 1] after the count, which still says what the method returned.
"$bin/vri-render" "${scene[@]}" --tf dense.yaml --step 2 --clamp -o clamped.exr --stats clamped.json
grep -q '"clamp": true' clamped.json || fail "the settings do not say clamp: true"
[ "$(jq -c .stats.out_of_range_pixels clamped.json)" = "$(jq -c .stats.out_of_range_pixels dense.json)" ] ||
  fail "--clamp changed the out-of-range count"
# Clamping lowers the largest value to 1: the largest change is max - 1, over all channels.
"$bin/vri-diff" dense.exr clamped.exr --json diff.json > /dev/null || true
awk -v d="$(jq '[.channels[].max_abs] | max' diff.json)" -v m="$(field dense.json max)" \
  'BEGIN { e = d - (m - 1); exit !(e < 1e-6 && e > -1e-6) }' || fail "clamped by $(jq '[.channels[].max_abs] | max' diff.json), not max - 1"
# Within range, --clamp changes no bit.
"$bin/vri-render" "${scene[@]}" --tf tf.yaml --step 0.25 --clamp -o faint-clamped.exr
"$bin/vri-diff" faint.exr faint-clamped.exr --fail 0 > /dev/null || fail "--clamp changed an image within [0, 1]"
"$bin/vri-reference" "${scene[@]}" --tf dense.yaml --clamp -o exact-clamped.exr
"$bin/vri-diff" exact.exr exact-clamped.exr --fail 0 > /dev/null || fail "--clamp changed the exact image"
echo "out-of-range counts and --clamp ok"
