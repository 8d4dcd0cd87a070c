#!/usr/bin/env bash
# The scene card (vri-render --describe, docs/scene-card.md): valid against its JSON Schema, and complete
# enough that examples/scene_card/render_from_card.py, which reads nothing else, reproduces vri-render's
# image on both grid conventions, all four placements, unequal spacings, a zoomed close-up, composite,
# the colour emission model, the analytic field, and jittered frames (the seed across 2^31 - 1).
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
bin=${VRI_BIN:?} src=${VRI_SOURCE:?}
python=/usr/bin/python3
source "$(dirname "${BASH_SOURCE[0]}")/lib/blob.sh" && write_blob_scene
cat > colour.yaml <<'YAML'
emission: color
points:
  - [0.0, 0.0, 0.0, 0.0, 0.0]
  - [0.4, 0.2, 0.1, 0.0, 0.3]
  - [0.4, 0.9, 0.6, 0.3, 1.2]
  - [1.0, 1.0, 1.0, 1.0, 0.5]
YAML

"$python" -c 'import jsonschema, numpy, OpenImageIO' 2> /dev/null || { echo "needs python3-jsonschema, -numpy, -openimageio: skipping"; exit 77; }
validate() {  # validate CARD: against docs/scene-card.schema.json
  "$python" - "$src/docs/scene-card.schema.json" "$1" <<'PY'
import json, sys, jsonschema
schema, card = (json.load(open(p)) for p in sys.argv[1:])
jsonschema.validate(card, schema)
PY
}

# Each case: a name, then vri-render's scene and method options. Double precision: the example's.
cases=(
  "cell_entry     --volume blob_8x8x8_uint8.raw --tf tf.yaml --placement entry --step 0.5"
  "node_entry     --volume blob_8x8x8_uint8.raw --tf tf.yaml --convention node --placement entry --step 0.5"
  "cell_eye       --volume blob_8x8x8_uint8.raw --tf tf.yaml --placement eye --step 0.7"
  "node_exit      --volume blob_8x8x8_uint8.raw --tf tf.yaml --convention node --placement entry-exit --step 0.3"
  "cell_corner    --volume blob_8x8x8_uint8.raw --tf tf.yaml --placement entry-exit-corner --step 0.6"
  "anisotropic    --volume blob_8x8x8_uint8.raw --tf tf.yaml --spacing 1,0.75,1.5 --placement eye --step 0.4 --eye 9,5,14"
  "zoomed         --volume blob_8x8x8_uint8.raw --tf tf.yaml --zoom 3 --zoom-centre 20,11 --step 0.25"
  "composite      --volume blob_8x8x8_uint8.raw --tf tf.yaml --method composite --placement entry-exit --step 0.5"
  "colour_model   --volume blob_8x8x8_uint8.raw --tf colour.yaml --method composite --convention node --step 0.5"
  "field          --field linear --tf colour.yaml --placement eye --step 0.5"
  "jitter         --volume blob_8x8x8_uint8.raw --tf tf.yaml --placement eye --step 0.7 --jitter --seed 7"
  "jitter_frames  --volume blob_8x8x8_uint8.raw --tf tf.yaml --convention node --placement entry-exit-corner --step 0.6 --jitter --seed 2147483647 --frames 3"
)
worst=0
for case in "${cases[@]}"; do
  read -r -a args <<< "$case"
  name=${args[0]} && args=("${args[@]:1}")
  method=(--method riemann)
  [[ " ${args[*]} " == *" --method "* ]] && method=()
  "$bin/vri-render" "${args[@]}" "${method[@]}" --precision double --size 40x30 -q -o "$name.vri.exr"
  voxels=()
  [[ " ${args[*]} " == *" --volume "* ]] && voxels=(--describe-voxels "$name.raw")
  "$bin/vri-render" "${args[@]}" "${method[@]}" --precision double --size 40x30 -q --describe "$name.card.json" "${voxels[@]}"
  validate "$name.card.json"
  "$python" "$src/examples/scene_card/render_from_card.py" "$name.card.json" "$name.mine.exr" > /dev/null
  # Bit for bit where NumPy's exp is the C library's; the stated tolerance is one float32 ulp of a channel.
  "$bin/vri-diff" "$name.vri.exr" "$name.mine.exr" --json "$name.diff.json" --fail 1e-6 > /dev/null ||
    { echo "$name: the card's renderer differs from vri-render"; "$bin/vri-diff" "$name.vri.exr" "$name.mine.exr"; exit 1; }
  max=$("$python" -c 'import json, sys; print(max(c["max_abs"] for c in json.load(open(sys.argv[1]))["channels"]))' "$name.diff.json")
  echo "$name: max |vri-render - card renderer| = $max"
done

# Every card's worked rays are the example's rays, and a point of each projects through the card's
# matrices to its pixel's centre (zoom included).
"$python" - "$src/examples/scene_card" *.card.json <<'PY'
import json, sys
import numpy as np
sys.path.insert(0, sys.argv[1])
import render_from_card as r
for path in sys.argv[2:]:
    card = json.load(open(path))
    cam = card["camera"]
    d = r.rays(card)
    P, V = np.array(cam["projection_matrix"]), np.array(cam["view_matrix"])
    for ray in card["worked_rays"]:
        i, j = ray["pixel"]
        assert np.array_equal(d[j * cam["width"] + i], np.array(ray["direction"])), (path, ray["pixel"])
        t = ray["t_near"] if ray["hits_box"] else 1.0
        clip = P @ V @ np.append(np.array(cam["eye"]) + t * np.array(ray["direction"]), 1.0)
        ndc = clip[:2] / clip[3]
        want = (2 * (i + 0.5) / cam["width"] - 1, 1 - 2 * (j + 0.5) / cam["height"])
        assert np.allclose(ndc, want, rtol=0, atol=1e-9), (path, ray["pixel"], ndc, want)
PY

# A card refuses what it cannot describe, in one line, and writes nothing.
source "$(dirname "${BASH_SOURCE[0]}")/lib/bad_input.sh"
write_blob_scene
E='^vri-render: error: '
bad 64 "${E}-o: --describe renders nothing, so it writes no -o" -- \
  "$bin/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml --describe c.json -o x.exr
bad 64 "${E}--describe-voxels requires --describe" -- \
  "$bin/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml --describe-voxels v.raw -o x.exr
bad 1 "${E}--describe-voxels: the scene is an analytic field, which has no voxels" -- \
  "$bin/vri-render" --field linear --tf tf.yaml --describe c.json --describe-voxels v.raw
bad 64 "${E}--output is required \(or --describe, which renders nothing\)" -- \
  "$bin/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml
# vri-outside's and vri-verify's own options (docs/tools/vri-outside.md, vri-verify.md).
O='^vri-outside: error: ' V='^vri-verify: error: '
scene=(--volume blob_8x8x8_uint8.raw --tf tf.yaml --size 8x6 -q)
bad 64 "${O}--renderer-image: expected exr, png or f32, got 'tiff'" -- \
  "$bin/vri-outside" "${scene[@]}" -o x.exr --renderer-image tiff -- /bin/true
bad 64 "${O}expected the renderer's command after -- " -- "$bin/vri-outside" "${scene[@]}" -o x.exr
bad 64 "${O}--timeout: expected a number > 0, got '0'" -- "$bin/vri-outside" "${scene[@]}" -o x.exr --timeout 0 -- /bin/true
bad 1 "${O}.*image.exr: the renderer wrote no image there" -- "$bin/vri-outside" "${scene[@]}" -o x.exr -- /bin/true
bad 64 "${V}--steps: expected at least 3 different steps" -- "$bin/vri-verify" "${scene[@]}" --steps 1,1,1 -- /bin/true
bad 64 "${V}--min-order: expected a number > 0, got 'nan'" -- "$bin/vri-verify" "${scene[@]}" --min-order nan -- /bin/true
bad 64 "${V}--method: vri-verify sweeps the step of a fixed-step method" -- \
  "$bin/vri-verify" "${scene[@]}" --method exact -- /bin/true
bad_done
echo "scene card: ${#cases[@]} cases reproduced from the card alone"
