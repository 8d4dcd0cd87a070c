#!/usr/bin/env bash
# vri-diff's PNG difference image is a heat map: the largest |A - B| over the channels through viridis,
# with a colour bar below the image; its scale is the largest difference, or 1/--diff-scale, and the
# JSON says which (heat_map.top); the gallery's caption names each heat map's scale.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
command -v oiiotool > /dev/null || { echo "oiiotool not installed: skipped"; exit 77; }

oiiotool --pattern constant:color=0.5,0.5,0.5,0.5 8x8 4 -d float -o a.exr
# One pixel off by 0.25 in G, another by 0.125 in A: the heat map takes the largest channel.
oiiotool a.exr --pattern constant:color=0,0.25,0,0 1x1 4 -d float --origin +3+2 --add -o b1.exr
oiiotool b1.exr --pattern constant:color=0,0,0,0.125 1x1 4 -d float --origin +5+6 --add -o b.exr
"$VRI_BIN/vri-diff" a.exr b.exr --diff-image heat.png --json d.json --failpercent 100 --warnpercent 100 > /dev/null
grep -q '"top": 0.25' d.json || fail "the scale: $(grep -A4 heat_map d.json)"
grep -q '"colormap": "viridis"' d.json || fail "the colour map: $(grep -A4 heat_map d.json)"
[[ $(oiiotool --info heat.png | tr -s " ") == *"8 x 32, 3 channel"* ]] || fail "size: $(oiiotool --info heat.png)"
# Bytes as a viewer reads them: 0 dark blue (68,1,84), the top yellow (253,231,37), half of it in between.
oiiotool --dumpdata heat.png > pixels.txt
pixel() { sed -n "s/^ *Pixel ($1, $2): \([0-9]* [0-9]* [0-9]*\) .*/\1/p" pixels.txt; }
[[ $(pixel 0 0) == "68 1 84" ]] || fail "zero: $(pixel 0 0)"
[[ $(pixel 3 2) == "253 231 37" ]] || fail "the largest error: $(pixel 3 2)"
read -r r g b <<< "$(pixel 5 6)"
(( g > 100 && g < 180 && b > 120 )) || fail "half the scale: $r $g $b"
[[ $(pixel 0 10) == "255 255 255" ]] || fail "the gap above the bar: $(pixel 0 10)"
[[ $(pixel 7 15) == "253 231 37" ]] || fail "the bar's right end: $(pixel 7 15)"
[[ $(pixel 0 27) == "0 0 0" ]] || fail "the tick at 0: $(pixel 0 27)"
# --diff-scale 2 sets the top at 0.5: the largest error is then half-way.
"$VRI_BIN/vri-diff" a.exr b.exr --diff-image heat2.png --diff-scale 2 --json d2.json --failpercent 100 --warnpercent 100 > /dev/null
grep -q '"top": 0.5' d2.json || fail "the scale with --diff-scale: $(grep -A4 heat_map d2.json)"
# An EXR difference image stays the exact per-channel difference (no heat map in the JSON).
"$VRI_BIN/vri-diff" a.exr b.exr --diff-image d.exr --json d3.json --failpercent 100 --warnpercent 100 > /dev/null
! grep -q heat_map d3.json || fail "an EXR diff image has a heat-map scale"

# The gallery states each heat map's scale, read from its comparison's JSON.
cat > tf.yaml <<'YAML'
points:
  - [0.0, 0.0, 0.0, 0.0, 0.0]
  - [1.0, 1.0, 0.6, 0.2, 0.8]
YAML
cat > exp.yaml <<'YAML'
name: heat
title: A heat map
paper: {paper: none, item: none, says: a test}
scenes:
  s: {field: linear, field_dims: [5, 5, 5], convention: node, tf: tf.yaml, size: [12, 8]}
methods:
  riemann: {step: [1, 0.25]}
comparisons:
  vs-fine: {reference: riemann-h0.25, runs: [riemann-h1], diff_image: png}
YAML
"$VRI_BIN/vri-run" --results out --gallery out exp.yaml 2> run.txt || fail "the run failed: $(cat run.txt)"
top=$(sed -n "s/^ *\"top\": \([0-9.e+-]*\),\?$/\1/p" out/heat/vs-fine-riemann-h1.json)
want=$(printf '%.3g' "$top")
grep -q "viridis from 0 (dark blue.*Top of the scale: vs-fine-riemann-h1 $want\.\*\$" out/README.md ||
    fail "the gallery's caption (top $top): $(grep -i heat out/README.md)"
echo "heat map: all checks passed"
