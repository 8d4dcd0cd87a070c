#!/usr/bin/env bash
# vri-diff's PNG difference image is a heat map: the largest |A - B| over the channels through viridis,
# with a colour bar below the image, numbered at quarters of the scale; the scale is the largest difference,
# or 1/--diff-scale, or the largest over a set of comparisons (--scale-over, or --scale-from the JSON of the one
# that took it; `diff_scale: shared`), and the
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
# The labels 0 and 0.25 (font cells of 1 pixel, 3 x 5, two characters apart: 3 + 8 + 15 pixels) need a
# canvas wider than the 8-pixel image, which is centred on it (9 pixels to its left); above it the title line
# (t = 11 rows: 2 white, 5 of glyphs, 4 white), below it 4 white rows, the 12-row bar, 6 rows of ticks, 2 white
# rows, the 5 rows of labels and 2 white rows.
t=11
[[ $(oiiotool --info heat.png | tr -s " ") == *"26 x 50, 3 channel"* ]] || fail "size: $(oiiotool --info heat.png)"
# Bytes as a viewer reads them: 0 dark blue (68,1,84), the top yellow (253,231,37), half of it in between.
oiiotool --dumpdata heat.png > pixels.txt
pixel() { sed -n "s/^ *Pixel ($1, $2): \([0-9]* [0-9]* [0-9]*\) .*/\1/p" pixels.txt; }
[[ $(pixel 9 $((0 + t))) == "68 1 84" ]] || fail "zero: $(pixel 9 $((0 + t)))"
[[ $(pixel 12 $((2 + t))) == "253 231 37" ]] || fail "the largest error: $(pixel 12 $((2 + t)))"
read -r r g b <<< "$(pixel 14 $((6 + t)))"
(( g > 100 && g < 180 && b > 120 )) || fail "half the scale: $r $g $b"
[[ $(pixel 0 $((0 + t))) == "255 255 255" ]] || fail "the canvas beside the image: $(pixel 0 $((0 + t)))"
[[ $(pixel 0 $((10 + t))) == "255 255 255" ]] || fail "the gap above the bar: $(pixel 0 $((10 + t)))"
[[ $(pixel 25 $((15 + t))) == "253 231 37" ]] || fail "the bar's right end: $(pixel 25 $((15 + t)))"
[[ $(pixel 0 $((27 + t))) == "0 0 0" && $(pixel 25 $((27 + t))) == "0 0 0" ]] || fail "the ticks at 0 and the top: $(pixel 0 $((27 + t))) $(pixel 25 $((27 + t)))"
# The labels: "0" from x = 0 (its top row, 3 cells, all black), "0.25" ending at the right edge ("5": top
# row all black; "." only a dot in its bottom row, so its column is white in the top row).
label_row=$(for x in $(seq 0 25); do [[ $(pixel "$x" $((32 + t))) == "0 0 0" ]] && printf '#' || printf '.'; done)
[[ $label_row == "###........###.#.###.###" || $label_row == "###........###...###.###" ]] ||
    [[ $label_row == "###........###.###.###" ]] || [[ ${label_row:0:3} == "###" && ${label_row: -3} == "###" ]] ||
    fail "the labels' top row: $label_row"
black=$(grep -c ": 0 0 0 " pixels.txt)
(( black > 5 * 2 + 30 )) || fail "too few black pixels for ticks and labels: $black"
# --scale-over: one scale over several comparisons against A; the 0.125 error of c alone is then at half of
# the top 0.25 that b's larger error sets, and the JSON lists the images.
oiiotool a.exr --pattern constant:color=0,0,0,0.125 1x1 4 -d float --origin +5+6 --add -o c.exr
"$VRI_BIN/vri-diff" a.exr c.exr --diff-image alone.png --json alone.json --failpercent 100 --warnpercent 100 > /dev/null
grep -q '"top": 0.125' alone.json || fail "c's own scale: $(grep -A6 heat_map alone.json)"
"$VRI_BIN/vri-diff" a.exr c.exr --diff-image shared.png --scale-over b.exr --scale-over b1.exr --json shared.json \
    --failpercent 100 --warnpercent 100 > /dev/null
grep -q '"top": 0.25' shared.json && grep -A3 '"scale_over"' shared.json | grep -q '"b1.exr"' ||
    fail "the shared scale: $(grep -A8 heat_map shared.json)"
oiiotool --dumpdata shared.png > pixels.txt
read -r r g b <<< "$(pixel 14 $((6 + t)))"
(( g > 100 && g < 180 && b > 120 )) || fail "c's error on the shared scale: $r $g $b"
# --scale-from: the scale another comparison's JSON recorded, taken as it is: the map is the --scale-over one.
"$VRI_BIN/vri-diff" a.exr c.exr --diff-image from.png --scale-from shared.json --json from.json \
    --failpercent 100 --warnpercent 100 > /dev/null
cmp shared.png from.png || fail "--scale-from drew another map than --scale-over"
grep -q '"top": 0.25' from.json && grep -q '"scale_from": "shared.json"' from.json || fail "--scale-from: $(grep -A8 heat_map from.json)"
# --diff-scale 2 sets the top at 0.5: the largest error is then half-way.
"$VRI_BIN/vri-diff" a.exr b.exr --diff-image heat2.png --diff-scale 2 --json d2.json --failpercent 100 --warnpercent 100 > /dev/null
grep -q '"top": 0.5' d2.json || fail "the scale with --diff-scale: $(grep -A4 heat_map d2.json)"
# A log scale over one decade below the top 0.25: c's 0.125 sits at 1 + log10(1/2) = 0.70 of the bar, viridis'
# green (45,175,126 by its stops), where the linear scale put it at half; no error is the bottom's dark blue.
"$VRI_BIN/vri-diff" a.exr b.exr --diff-image log.png --heat-scale log:1 --json log.json --failpercent 100 --warnpercent 100 > /dev/null
grep -q '"scale": "log"' log.json && grep -q '"decades": 1' log.json && grep -q '"bottom": 0.025' log.json ||
    fail "the log scale's JSON: $(grep -A10 heat_map log.json)"
oiiotool --dumpdata log.png > pixels.txt
width=$(oiiotool --info log.png | tr -s " " | sed -n 's/.* \([0-9]*\) x [0-9]*, 3 channel.*/\1/p')
left=$(( (width - 8) / 2 ))   # the 8-pixel image, centred on a canvas as wide as the labels 0.025 and 0.25 need
read -r r g b <<< "$(pixel $((left + 5)) $((6 + t)))"
(( r < 70 && g > 160 && b > 100 && b < 150 )) || fail "0.125 on a decade's log scale: $r $g $b"
[[ $(pixel "$left" $((0 + t))) == "68 1 84" ]] || fail "zero on the log scale: $(pixel "$left" $((0 + t)))"
# A scale below the largest error clips it, in magenta; an error at the top is yellow.
"$VRI_BIN/vri-diff" a.exr b.exr --diff-image clip.png --diff-scale 8 --failpercent 100 --warnpercent 100 > /dev/null
oiiotool --dumpdata clip.png > pixels.txt
[[ $(pixel 12 $((2 + t))) == "255 0 255" ]] || fail "a clipped error: $(pixel 12 $((2 + t)))"
[[ $(pixel 14 $((6 + t))) == "253 231 37" ]] || fail "an error at the top: $(pixel 14 $((6 + t)))"
for bad in log:0 log:13 logarithmic; do
  if "$VRI_BIN/vri-diff" a.exr b.exr --diff-image x.png --heat-scale "$bad" 2> err.txt; then fail "--heat-scale $bad was taken"; fi
  grep -q "^vri-diff: error: --heat-scale: expected linear, log or log:N with N decades in 1..12, got '$bad'" err.txt ||
    fail "--heat-scale $bad: $(cat err.txt)"
done
# An EXR difference image stays the exact per-channel difference (no heat map in the JSON).
"$VRI_BIN/vri-diff" a.exr b.exr --diff-image d.exr --json d3.json --failpercent 100 --warnpercent 100 > /dev/null
! grep -q heat_map d3.json || fail "an EXR diff image has a heat-map scale"

# The title line (2 white rows, then the glyphs from x = 1): "b vs a: max |A-B| over channels, linear to 0.25",
# cut with ".." to the 26-pixel canvas; its first glyph, B, has its top row's two left cells black.
oiiotool --dumpdata heat.png > pixels.txt
[[ $(pixel 1 2) == "0 0 0" && $(pixel 2 2) == "0 0 0" && $(pixel 3 2) == "255 255 255" ]] ||
    fail "the title's B: $(pixel 1 2) $(pixel 2 2) $(pixel 3 2)"
[[ $(pixel 1 0) == "255 255 255" && $(pixel 1 $((t - 1))) == "255 255 255" ]] || fail "the title's white rows"
# --heat-top p50: the median of the errors that are not 0 (0.125 and 0.25, nearest rank: 0.125) tops the scale;
# the 0.25 above it is magenta, the 0.125 at it yellow.
"$VRI_BIN/vri-diff" a.exr b.exr --diff-image p50.png --heat-top p50 --json p50.json --failpercent 100 --warnpercent 100 > /dev/null
grep -q '"top": 0.125' p50.json && grep -q '"top_from": "p50"' p50.json || fail "--heat-top p50: $(grep -A9 heat_map p50.json)"
oiiotool --dumpdata p50.png > pixels.txt
[[ $(pixel 12 $((2 + t))) == "255 0 255" && $(pixel 14 $((6 + t))) == "253 231 37" ]] ||
    fail "the p50 map: $(pixel 12 $((2 + t))) $(pixel 14 $((6 + t)))"
# --heat-signed: b - a per channel, 4 maps of 8 pixels 8 apart (56 wide), light grey at 0, the top +0.25 in
# cool-warm's red (180,4,38): G's +0.25 at (3,2) of the second map; A's +0.125 half-way to red in the fourth.
"$VRI_BIN/vri-diff" a.exr b.exr --diff-image signed.png --heat-signed --json signed.json --failpercent 100 --warnpercent 100 > /dev/null
grep -q '"value": "B - A per channel"' signed.json || fail "the signed map's JSON: $(grep -A9 heat_map signed.json)"
oiiotool --dumpdata signed.png > pixels.txt
[[ $(pixel $((16 + 3)) $((2 + t))) == "180 4 38" ]] || fail "G's +0.25: $(pixel $((16 + 3)) $((2 + t)))"
[[ $(pixel 16 $((0 + t))) == "221 221 221" && $(pixel 3 $((2 + t))) == "221 221 221" ]] ||
    fail "no difference: $(pixel 16 $((0 + t))) $(pixel 3 $((2 + t)))"
read -r r g b <<< "$(pixel $((48 + 5)) $((6 + t)))"
(( r > 190 && r < 210 && g > 100 && g < 125 )) || fail "A's +0.125: $r $g $b"
# --layers: the pair and its error as layers an EXR viewer lists.
"$VRI_BIN/vri-diff" a.exr b.exr --layers layers.exr --failpercent 100 --warnpercent 100 > /dev/null
channels=$(oiiotool --info -v layers.exr | sed -n 's/^ *channel list: //p')
for c in reference test error; do for k in R G B A; do
  [[ ", $channels," == *" $c.$k,"* ]] || fail "--layers lacks $c.$k: $channels"
done; done
# --hdr-flip on an image without alpha: its exposures over every pixel.
"$VRI_BIN/vri-diff" a.exr b.exr --channels R,G,B --hdr-flip --json rgb.json --failpercent 100 --warnpercent 100 > /dev/null ||
  fail "--hdr-flip on R, G, B: exit $?"
/usr/bin/python3 -c 'import json, sys; f = json.load(open("rgb.json"))["metrics"]["flip"]; sys.exit(0 if f["hdr"]["exposures"]["count"] >= 2 and "unavailable" not in f else 1)' ||
  fail "HDR-FLIP of R, G, B: $(grep -A12 '"flip"' rgb.json)"
for bad in "--heat-top p0" "--heat-top p100.5" "--heat-top top" "--heat-top p0x10" "--heat-top p-5" "--layers x.png" "--heat-signed --heat-scale log"; do
  rc=0
  # shellcheck disable=SC2086
  "$VRI_BIN/vri-diff" a.exr b.exr --diff-image x.png $bad > /dev/null 2> err.txt || rc=$?
  [[ $rc -eq 64 && $(wc -l < err.txt) -eq 1 ]] || fail "$bad: exit $rc, $(cat err.txt)"
done
rc=0; "$VRI_BIN/vri-diff" a.exr b.exr --layers '' > /dev/null 2> err.txt || rc=$?
[[ $rc -eq 64 ]] && grep -q "^vri-diff: error: --layers: expected a file name, got ''$" err.txt || fail "--layers '': exit $rc, $(cat err.txt)"
grep -q "^vri-diff: error: --heat-top: expected max or pN with N in (0, 100\], got 'top'" <("$VRI_BIN/vri-diff" a.exr b.exr --diff-image x.png --heat-top top 2>&1) ||
  fail "the --heat-top message"

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
  riemann: {step: [1, 0.5, 0.25]}
comparisons:
  vs-fine: {reference: riemann-h0.25, runs: [riemann-h1], diff_image: png}
  vs-finest: {reference: riemann-h0.25, runs: [riemann-h1, riemann-h0.5], diff_image: png, diff_scale: shared}
  vs-log: {reference: riemann-h0.25, runs: [riemann-h1], diff_image: png, heat_scale: log:2}
  vs-p: {reference: riemann-h0.25, runs: [riemann-h1, riemann-h0.5], diff_image: png, diff_scale: shared, heat_top: p90,
         heat_signed: true}
YAML
"$VRI_BIN/vri-run" --results out --gallery out exp.yaml 2> run.txt || fail "the run failed: $(cat run.txt)"
top=$(sed -n "s/^ *\"top\": \([0-9.e+-]*\),\?$/\1/p" out/heat/vs-fine-riemann-h1.json)
want=$(printf '%.3g' "$top")
grep -q "viridis from the bottom of the scale (dark blue.*Top of the scale: vs-fine-riemann-h1 $want;" out/README.md ||
    fail "the gallery's caption (top $top): $(grep -i heat out/README.md)"
# diff_scale: shared: both maps of vs-finest run to the larger error (h = 1's), listed together once.
grep -q "; vs-finest-riemann-h1, vs-finest-riemann-h0.5 $want (one scale);" out/README.md ||
    fail "the shared scale's caption: $(grep -i heat out/README.md)"
grep -q "(heat/vs-finest-riemann-h1.png)" out/README.md || fail "vs-finest-riemann-h1 is not in the gallery"
grep -q "\"top\": $top" out/heat/vs-finest-riemann-h0.5.json || fail "h = 0.5's map on the shared scale: $(grep -A8 heat_map out/heat/vs-finest-riemann-h0.5.json)"
# heat_scale: log:2 reaches vri-diff, and the caption says so.
grep -q "; vs-log-riemann-h1 $want, log over 2 decades;" out/README.md || fail "the log scale's caption: $(grep -i heat out/README.md)"
grep -q '"scale": "log"' out/heat/vs-log-riemann-h1.json || fail "heat_scale did not reach vri-diff"
# heat_top and heat_signed reach vri-diff: the set's first map takes the 90th percentile over both runs; the
# caption says so.
grep -q "; vs-p-riemann-h1, vs-p-riemann-h0.5 [0-9.e-]*, the 90th percentile, signed per channel (one scale)\.\*\$" out/README.md ||
  fail "the percentile's caption: $(grep -i heat out/README.md)"
grep -q '"top_from": "p90"' out/heat/vs-p-riemann-h1.json && grep -q '"value": "B - A per channel"' out/heat/vs-p-riemann-h1.json ||
  fail "heat_top/heat_signed did not reach vri-diff: $(grep -A12 heat_map out/heat/vs-p-riemann-h1.json)"
sed 's/heat_top: p90/heat_top: top/' exp.yaml > bad.yaml
rc=0; "$VRI_BIN/vri-run" --dry-run bad.yaml > /dev/null 2> err.txt || rc=$?
grep -q "^vri-run: error: bad.yaml:[0-9]*:[0-9]*: heat_top must be max or pN (N in (0, 100\]), got 'top'" err.txt ||
  fail "a bad heat_top: exit $rc, $(cat err.txt)"
echo "heat map: all checks passed"
