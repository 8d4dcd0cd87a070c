#!/usr/bin/env bash
# Extinction from 1e-6 to 1e300 per voxel on the blob scene, every method in double and float (and on
# the Vulkan backend when there is a device), and vri-reference's Riemann method: each run either
# exits 0 with an image whose every value is finite (counted by oiiotool, not by vri) or fails with
# one error line and writes nothing. --allow-nonfinite writes the overflowed image, warns, and its
# stats count the pixels. Skipped (77) without oiiotool.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
command -v oiiotool > /dev/null || { echo "oiiotool not installed: skipping"; exit 77; }
source "$(dirname "${BASH_SOURCE[0]}")/lib/blob.sh" && write_blob_volume

write_tf() {  # write_tf TAU: the blob's transfer function with TAU where it is visible
  printf 'points:\n  - [0.0, 0, 0, 0, 0]\n  - [0.3, 0, 0, 0, 0]\n  - [0.7, 1, 0.5, 0.2, %s]\n  - [1.0, 1, 1, 1, %s]\n' \
    "$1" "$1" > tf.yaml
}
# The number of NaN and infinite values over all channels, as oiiotool counts them.
nonfinite_values() {
  oiiotool "$1" --printstats | awk '/NanCount|InfCount/ { for (i = 3; i <= NF; ++i) n += $i } END { print n + 0 }'
}
# The images the runs wrote, checked together at the end: oiiotool takes half a second to start, the renders a
# tenth of that. finite/N.exr is run N's image, finite/N.label its label.
mkdir finite

finite=0 refused=0
# check LABEL TOOL ARGS...: one run, then either a finite image or one error line and no image.
check() {
  local label=$1 tool=$2
  shift 2
  rm -f out.exr
  local rc=0
  "$VRI_BIN/$tool" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 16x12 --eye 4,4,-20 --target 4,4,4 -q \
    -o out.exr "$@" 2> err.txt || rc=$?
  if [ "$rc" -eq 0 ]; then
    [ ! -s err.txt ] || fail "$label: exit 0 with messages: $(cat err.txt)"
    finite=$((finite + 1))
    mv out.exr "finite/$finite.exr"
    echo "$label" > "finite/$finite.label"
  else
    [ "$rc" -eq 1 ] || fail "$label: exit $rc, expected 0 or 1: $(cat err.txt)"
    [ "$(wc -l < err.txt)" -eq 1 ] || fail "$label: expected one error line, got: $(cat err.txt)"
    grep -Eq "^$tool: error: (the image: [0-9]+ of 192 pixels are not finite \(first at [0-9]+,[0-9]+: R=|transfer function point 2 holds .* beyond the range of float)" err.txt ||
      fail "$label: unclear error: $(cat err.txt)"
    [ ! -e out.exr ] || fail "$label: failed but wrote the image"
    refused=$((refused + 1))
  fi
}

vulkan=false
"$VRI_BIN/vri-render" --list-devices > /dev/null 2>&1 && vulkan=true
taus="1e-6 1 1e10 1e39 1e300"  # each decade would do; these cross float's and Simpson's limits
for tau in $taus; do
  write_tf "$tau"
  for method in riemann composite simpson coupled decoupled; do
    for precision in double float; do
      check "tau $tau $method $precision" vri-render --method $method --precision $precision
    done
  done
  if $vulkan; then  # one fixed-step and one adaptive method: a device start costs more than a CPU render
    check "tau $tau riemann vulkan" vri-render --method riemann --backend vulkan
    check "tau $tau coupled vulkan" vri-render --method coupled --backend vulkan
  fi
  check "tau $tau vri-reference riemann" vri-reference --method riemann --step 0.1
done
# Both outcomes occur: small extinctions render, huge ones overflow (Riemann's tau * dx * C beyond
# float at 1e39, Simpson's extrapolated optical depth at much less).
[ "$finite" -gt 0 ] && [ "$refused" -gt 0 ] || fail "expected finite and refused runs, got $finite and $refused"
# Every image a run wrote with exit 0 is finite: oiiotool's NaN and Inf counts, an image at a time.
oiiotool_args=()
for n in $(seq "$finite"); do oiiotool_args+=("finite/$n.exr" --echo "image $n" --printstats); done
oiiotool "${oiiotool_args[@]}" > stats.txt || fail "oiiotool could not read the images: $(tail -3 stats.txt)"
awk '/^image [0-9]+$/ { n = $2 } /NanCount|InfCount/ { for (i = 3; i <= NF; ++i) if ($i != 0) print n }' stats.txt |
  sort -u > nonfinite.txt
[ "$(grep -c '^image ' stats.txt)" -eq "$finite" ] || fail "oiiotool reported $(grep -c '^image ' stats.txt) of $finite images"
[ ! -s nonfinite.txt ] ||
  fail "$(cat "finite/$(head -1 nonfinite.txt).label"): exit 0 with non-finite values in the image ($(wc -l < nonfinite.txt) such runs)"
echo "$finite finite images, $refused runs refused"

# --allow-nonfinite: the image is written, one warning, and the stats count what oiiotool finds.
write_tf 1e300
"$VRI_BIN/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 16x12 --eye 4,4,-20 --target 4,4,4 -q \
  --method riemann --allow-nonfinite -o allowed.exr --stats allowed.json 2> err.txt
[ "$(nonfinite_values allowed.exr)" -gt 0 ] || fail "--allow-nonfinite: the image is finite; the test lost its point"
grep -Eq '^vri-render: warning: the image: [0-9]+ of 192 pixels are not finite' err.txt && [ "$(wc -l < err.txt)" -eq 1 ] ||
  fail "--allow-nonfinite: expected one warning, got: $(cat err.txt)"
count=$(grep -o '"nonfinite_pixels": [0-9]*' allowed.json | grep -o '[0-9]*$')
[ "$count" -gt 0 ] && grep -q "the image: $count of 192 pixels" err.txt ||
  fail "--allow-nonfinite: the stats count ($count) is not the warning's: $(cat err.txt)"
# A finite render records zero.
write_tf 1
"$VRI_BIN/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 16x12 -q -o ok.exr --stats ok.json
grep -q '"nonfinite_pixels": 0' ok.json || fail "a finite render does not record nonfinite_pixels 0"
