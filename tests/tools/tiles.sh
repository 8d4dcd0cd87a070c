#!/usr/bin/env bash
# One render as tiles: vri-render and vri-reference with --region compute the pixels of the whole image
# bit for bit (every method and path: Riemann double, SIMD float, the scalar float loop, composite with
# early termination, the adaptive Simpson methods, exact in vri-render and vri-reference, Vulkan where
# there is a device), vri-merge-tiles joins 2, 3 or 4 tiles, even or not, bands or not, into the untiled
# image with the untiled counts, and an experiment's `tiles:` gives the untiled run's files, cached as
# any step.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
bin=${VRI_BIN:?}
source "$(dirname "${BASH_SOURCE[0]}")/lib/blob.sh" && write_blob_scene
W=41 H=29

# tiled TOOL "REGION..." ARGS...: renders the whole image and each region with the same options, merges
# the tiles and checks the merge against the whole: pixels bit for bit, counts and bounds equal.
tiled() {
  local tool=$1 regions=$2
  shift 2
  local scene=(--volume blob_8x8x8_uint8.raw --tf tf.yaml --size ${W}x$H -q)
  "$bin/$tool" "${scene[@]}" "$@" -o whole.exr --stats whole.json
  local merge=() k=0
  for region in $regions; do
    k=$((k + 1))
    "$bin/$tool" "${scene[@]}" "$@" --region "$region" -o "tile$k.exr" --stats "tile$k.json"
    merge+=(--tile "tile$k.exr" "tile$k.json")
  done
  "$bin/vri-merge-tiles" "${merge[@]}" -o merged.exr --stats merged.json --png merged.png
  "$bin/vri-diff" merged.exr whole.exr --fail 0 > /dev/null || fail "$tool $* as $regions: the merged image differs"
  /usr/bin/python3 - "$k" <<'PY' || fail "$tool $* as $regions: the merged stats"
import json, sys
whole, merged = json.load(open("whole.json")), json.load(open("merged.json"))
tiles = [json.load(open(f"tile{k}.json")) for k in range(1, int(sys.argv[1]) + 1)]
assert all("region" in t for t in tiles) and "region" not in merged and "region" not in whole, "region"
assert merged["tool"] == whole["tool"] and merged["options"] == whole["options"], "tool, options"
assert merged["camera"] == whole["camera"] and merged["scene"] == whole["scene"], "camera, scene"
assert len(merged["tiles"]) == len(tiles) and merged["merged_by"]["tool"] == "vri-merge-tiles", "tiles"
s, w = merged["stats"], whole["stats"]
# Every count is a sum over pixels, each computed as in the whole image: the same totals.
per_pixel = ["rays", "rays_hit", "samples_placed", "samples_evaluated", "rays_terminated", "rays_opaque", "pieces",
             "pieces_visible", "sub_pieces", "quadrature_intervals", "quadrature_nodes", "nonfinite_pixels",
             "termination_left_out_max", "adaptive", "out_of_range_pixels"]
for key in per_pixel:
    assert s.get(key) == w.get(key), (key, s.get(key), w.get(key))
for key in ["simd_target", "voxel_loads"]:  # what ran, kept where the tiles agree
    assert s.get(key) == w.get(key), (key, s.get(key), w.get(key))
if "error_bound" in w:
    assert s["error_bound"]["max"] == w["error_bound"]["max"], "error_bound.max"
    for m, x in zip(s["error_bound"]["mean"], w["error_bound"]["mean"]):
        assert abs(m - x) <= 1e-12 * max(abs(x), 1e-300), ("error_bound.mean", m, x)
assert abs(s["wall_seconds"] - sum(t["stats"]["wall_seconds"] for t in tiles)) < 1e-9, "wall_seconds"
assert merged["timing"]["repeats"] == whole["timing"]["repeats"], "repeats"
assert sum(t["stats"]["rays"] for t in tiles) == w["rays"] == whole["camera"]["width"] * whole["camera"]["height"]
PY
}

# Riemann in double (the scalar loop): 2 even bands, 3 uneven ones, 4 rectangles that are not bands.
tiled vri-render "0,0,$W,14 0,14,$W,15"
tiled vri-render "0,0,$W,9 0,9,$W,1 0,10,$W,19" --step 0.3 --placement entry-exit-corner
tiled vri-render "0,0,17,11 17,0,24,11 0,11,5,18 5,11,36,18" --step 0.3 --placement eye
# Float: the SIMD packets (pixels enter them in 4x4 blocks of a tile, so regions that cut blocks), and
# the scalar float loop; composite with early termination ended by its bound.
tiled vri-render "0,0,$W,7 0,7,$W,22" --precision float --step 0.3
tiled vri-render "0,0,21,29 21,0,20,29" --precision float --method composite --step 0.3 --early-termination auto
tiled vri-render "0,0,$W,10 0,10,$W,10 0,20,$W,9" --precision float --simd off --step 0.3
# AVX2's packets, where the host has it: the merge keeps the target and the way voxels were loaded.
if "$bin/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 8x6 -q -o probe.exr --stats - |
  /usr/bin/python3 -c 'import json, sys; sys.exit("AVX2" not in json.load(sys.stdin)["machine"]["simd_targets"])'; then
  tiled vri-render "0,0,$W,7 0,7,$W,22" --precision float --step 0.3 --simd AVX2
  /usr/bin/python3 -c 'import json; assert json.load(open("merged.json"))["stats"]["voxel_loads"] in ("gather", "scalar")' ||
    fail "merged AVX2 tiles: stats.voxel_loads"
fi
# Paper B's adaptive Simpson (each ray's steps its own) and uniform Simpson.
tiled vri-render "0,0,$W,13 0,13,$W,16" --method coupled --tolerance 0.001
tiled vri-render "0,0,$W,5 0,5,$W,24" --method decoupled --tolerance 0.001 --h-max 2 --precision float
tiled vri-render "0,0,30,29 30,0,11,29" --method simpson --step 0.5 --no-skip-empty
# The exact method: vri-render's, and vri-reference's (with its error bounds) and paper B's reference.
tiled vri-render "0,0,$W,15 0,15,$W,14" --method exact
tiled vri-reference "0,0,$W,3 0,3,$W,11 0,14,$W,7 0,21,$W,8" --repeat 2
tiled vri-reference "0,0,$W,20 0,20,$W,9" --method riemann --step 0.05
# A region of the analytic field.
"$bin/vri-render" --field linear --tf tf.yaml --size 9x7 -q -o field.exr
"$bin/vri-render" --field linear --tf tf.yaml --size 9x7 -q --region 0,0,9,3 -o f1.exr --stats f1.json
"$bin/vri-render" --field linear --tf tf.yaml --size 9x7 -q --region 0,3,9,4 -o f2.exr --stats f2.json
"$bin/vri-merge-tiles" --tile f2.exr f2.json --tile f1.exr f1.json -o field-merged.exr  # in any order
"$bin/vri-diff" field-merged.exr field.exr --fail 0 > /dev/null || fail "the analytic field's tiles"
# The logged ray of a region is the whole image's pixel, logged the same.
"$bin/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size ${W}x$H -q --method coupled --log-ray 20,20 \
  --log whole-ray.csv -o a.exr
"$bin/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size ${W}x$H -q --method coupled --log-ray 20,20 \
  --log tile-ray.csv --region 10,15,20,10 -o b.exr
cmp whole-ray.csv tile-ray.csv || fail "--log-ray in a region: another log"
# The region says where it lies, in the stats and in the image's attributes.
/usr/bin/python3 -c 'import json; r = json.load(open("tile2.json"))["region"]; assert r == {"x": 0, "y": 20, "width": 41, "height": 9}, r' ||
  fail "the stats' region"

# Vulkan (lavapipe here): the shaders' rays are the whole image's.
if built_with_vulkan && "$bin/vri-render" --list-devices > /dev/null 2>&1; then
  tiled vri-render "0,0,$W,11 0,11,$W,18" --backend vulkan --step 0.3
  tiled vri-render "0,0,20,29 20,0,21,29" --backend vulkan --method coupled --tolerance 0.001
  vulkan="Vulkan"
else
  vulkan="no Vulkan device"
fi

# An experiment with `tiles:` writes the untiled experiment's files: the same image and preview.
cat > plain.yaml <<'YAML'
name: plain
title: A small render
paper: {paper: none, item: tiles, says: a test}
scenes:
  blob: {volume: blob_8x8x8_uint8.raw, convention: cell, tf: tf.yaml, size: [23, 17], png: {invert: true}}
methods:
  riemann: {step: 0.3}
references:
  exact: {method: exact, eps: 1e-9}
comparisons:
  vs-exact: {reference: exact}
YAML
sed -e 's/^name: plain/name: tiled/' -e 's/riemann: {step: 0.3}/riemann: {step: 0.3, tiles: 3}/' \
  -e 's/exact: {method: exact, eps: 1e-9}/exact: {method: exact, eps: 1e-9, tiles: 4}/' plain.yaml > tiled.yaml
"$bin/vri-run" --dry-run --results out tiled.yaml > commands.txt
[ "$(grep -c -- '--region' commands.txt)" -eq 7 ] || fail "--dry-run: expected 7 tile commands: $(cat commands.txt)"
grep -q -- "vri-render .*--region 0,5,23,6 -o out/tiled/riemann.tile-2.exr --stats out/tiled/riemann.tile-2.json" \
  commands.txt || fail "--dry-run: the second tile of riemann: $(cat commands.txt)"
grep -q -- "vri-merge-tiles --tile out/tiled/exact.tile-1.exr out/tiled/exact.tile-1.json .*--png-invert -o out/tiled/exact.exr --png out/tiled/exact.png --stats out/tiled/exact.json" \
  commands.txt || fail "--dry-run: the merge of exact: $(cat commands.txt)"
"$bin/vri-run" --results out plain.yaml 2> /dev/null
"$bin/vri-run" --results out tiled.yaml 2> first.txt
grep -q "tiled: 10 steps, 10 ran, 0 cached" first.txt || fail "the tiled experiment: $(cat first.txt)"
for run in riemann exact; do
  "$bin/vri-diff" "out/tiled/$run.exr" "out/plain/$run.exr" --fail 0 > /dev/null || fail "tiled experiment: $run.exr"
  cmp "out/tiled/$run.png" "out/plain/$run.png" || fail "tiled experiment: $run.png"
done
/usr/bin/python3 - <<'PY' || fail "tiled experiment: the comparison"
import json
a, b = (json.load(open(f"out/{e}/vs-exact-riemann.json")) for e in ("plain", "tiled"))
assert a["channels"] == b["channels"], "the diff against the reference"
PY
"$bin/vri-run" --results out tiled.yaml 2> second.txt
grep -q "tiled: 10 steps, 0 ran, 10 cached" second.txt || fail "the tiled experiment again: $(cat second.txt)"

echo "tiles: 14 tiled renders bitwise equal to the untiled ones ($vulkan); tiled experiment = untiled, cached"
