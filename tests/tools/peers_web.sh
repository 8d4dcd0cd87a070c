#!/usr/bin/env bash
# The web peers (tools/peers/web, docs/peers-web.md): three.js's VolumeRenderShader1, vtk.js and NiiVue in
# headless Chromium, each reading only a scene card. On a small asymmetric volume (and on Bonsai at 80x60 when
# the volumes are here) each adapter's image must have the card's size, cover what vri's covers, and sit closer
# to vri-render's Riemann image of the card than its own image does flipped upside down or mirrored, and (the
# perspective renderers) closer than to a wider field of view. The mean-error bounds are loose, about 1.5 times
# what each library measured here (its own error floor: three.js's half-voxel shift, NiiVue's orthographic
# view and fixed step; docs/peers-web.md).
# Also: the stats record, --step, and a refused card. Nothing here depends on timing.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
bin=$VRI_BIN
web=$VRI_SOURCE/tools/peers/web
[ -x /usr/bin/chromium ] || { echo "no /usr/bin/chromium (make deps installs it): skipping"; exit 77; }
command -v node >/dev/null || { echo "no node: skipping"; exit 77; }
[ -d "$web/node_modules/playwright-core" ] || { echo "no $web/node_modules (make deps runs npm ci there): skipping"; exit 77; }
/usr/bin/python3 -c 'import numpy, OpenImageIO' 2>/dev/null || { echo "python3-numpy or python3-openimageio not installed: skipping"; exit 77; }

# An adapter's output (.f32: raw float32 RGBA, premultiplied; .png: 8-bit with straight alpha, which OpenImageIO
# premultiplies as it reads) as float RGBA EXR, checked for the card's size, and as it would be flipped upside
# down and mirrored left to right: OUT.exr, OUT.flipped.exr, OUT.flopped.exr. Prints the coverage: of the pixels
# vri's image VRI covers (alpha > 0.05), the share the adapter's covers too (alpha > 0.01). One interpreter for
# all four, which import numpy and OpenImageIO in half a second.
exr_and_coverage() {
  /usr/bin/python3 - "$@" <<'EOF'
import json, sys, numpy as np, OpenImageIO as oiio
src, out, card, vri = sys.argv[1:5]
cam = json.load(open(card))["camera"]
w, h = cam["width"], cam["height"]
if src.endswith(".f32"):
    raw = np.fromfile(src, "<f4")
    if raw.size != w * h * 4:
        sys.exit(f"{src}: {raw.size} floats, not {w} x {h} x 4")
    img = raw.reshape(h, w, 4)
else:
    inp = oiio.ImageInput.open(src)
    spec = inp.spec()
    if (spec.width, spec.height, spec.nchannels) != (w, h, 4):
        sys.exit(f"{src}: {spec.width} x {spec.height} x {spec.nchannels}, not {w} x {h} x 4")
    img = inp.read_image(oiio.FLOAT)
    inp.close()
for suffix, pixels in (("", img), (".flipped", img[::-1]), (".flopped", img[:, ::-1])):
    dst = f"{out}{suffix}.exr"
    o = oiio.ImageOutput.create(dst)
    o.open(dst, oiio.ImageSpec(w, h, 4, "float"))
    o.write_image(np.ascontiguousarray(pixels, dtype=np.float32))
    o.close()
covered = oiio.ImageBuf(vri).get_pixels(oiio.FLOAT)[..., 3] > 0.05
print(np.count_nonzero(img[..., 3][covered] > 0.01) / max(np.count_nonzero(covered), 1))
EOF
}
# The mean absolute error over all channels, from vri-diff's JSON.
mean_error() {
  "$bin/vri-diff" "$1" "$2" --failpercent 100 --warnpercent 100 --json - |
    /usr/bin/python3 -c 'import json, sys; c = json.load(sys.stdin)["channels"]; print(sum(x["mean_abs"] for x in c) / len(c))'
}
below() { /usr/bin/python3 -c "import sys; sys.exit(not $1 < $2)"; }

# check_adapter SCENE ADAPTER EXTENSION LIMIT [perspective]: runs it on SCENE/card.json and checks its image:
# closer to vri's than flipped or mirrored, and with `perspective`, than to the wider view (NiiVue's view is
# orthographic, matched at the target's depth only, so on a close camera a wider view can fit it as well).
check_adapter() {
  local scene=$1 adapter=$2 ext=$3 limit=$4 out good flipped flopped wide cover
  out=$scene/$adapter
  node "$web/$adapter.mjs" "$scene/card.json" "$out.$ext" "$out.json" || fail "$adapter on $scene: exit $?"
  cover=$(exr_and_coverage "$out.$ext" "$out" "$scene/card.json" "$scene/vri.exr") || fail "$adapter on $scene: bad image"
  below 0.5 "$cover" || fail "$adapter on $scene: covers only $cover of vri's pixels"
  good=$(mean_error "$scene/vri.exr" "$out.exr")
  flipped=$(mean_error "$scene/vri.exr" "$out.flipped.exr")
  flopped=$(mean_error "$scene/vri.exr" "$out.flopped.exr")
  wide=$(mean_error "$scene/wide.exr" "$out.exr")
  echo "$adapter on $scene: mean error $good against vri (flipped $flipped, mirrored $flopped; against the wider view $wide; coverage $cover)"
  below "$good" "$limit" || fail "$adapter on $scene: mean error $good against vri's image, above $limit"
  below "$good" "$flipped" || fail "$adapter on $scene: its image flipped is as close to vri's ($flipped) as itself ($good)"
  below "$good" "$flopped" || fail "$adapter on $scene: its image mirrored is as close to vri's ($flopped) as itself ($good)"
  [ "${5:-}" != perspective ] || below "$good" "$wide" || fail "$adapter on $scene: as close to a wider view ($wide) as to the card's ($good)"
}

# scene NAME FOV VRI-OPTIONS... (absolute paths): the card (with its voxels), vri-render's Riemann image of it, and the same scene
# seen with a field of view 10 degrees wider (a wrong camera).
scene() {
  local name=$1 fov=$2
  shift 2
  mkdir -p "$name"
  # Written from inside the scene's folder: the card names its voxels file as given, and a reader finds it
  # relative to the card's folder (as examples/scene_card/render_from_card.py does).
  (cd "$name" && "$bin/vri-render" "$@" --fov "$fov" --method riemann --step 0.5 --describe card.json --describe-voxels voxels.raw -q)
  "$bin/vri-render" "$@" --fov "$fov" --method riemann --step 0.5 -q -o "$name/vri.exr"
  "$bin/vri-render" "$@" --fov "$((fov + 10))" --method riemann --step 0.5 -q -o "$name/wide.exr"
}

# A 12^3 volume: zero on its faces, an off-centre blob on a ramp (lib/peer_scene.sh), seen obliquely.
source "$(dirname "${BASH_SOURCE[0]}")/lib/peer_scene.sh" && write_peer_scene
scene small 35 --volume "$PWD/vol_12x12x12_uint8.raw" --tf "$PWD/tf.yaml" --size 48x36 --eye 16,21,-22 --target 6,6,6 --up 0,1,0
# Measured mean errors against vri's image: three.js 0.029, vtk.js 0.0049, NiiVue 0.029.
check_adapter small three f32 0.045 perspective
check_adapter small vtkjs png 0.0075 perspective
check_adapter small niivue png 0.045

# The stats: the documented record, the library's version, one time per frame, the image's quantisation.
/usr/bin/python3 - small/three.json small/vtkjs.json small/niivue.json <<'EOF' || fail "stats: $(cat small/three.json)"
import json, sys
for path, name, quantisation in zip(sys.argv[1:], ["three.js", "vtk.js", "NiiVue"], ["float32", "8-bit", "8-bit"]):
    s = json.load(open(path))
    assert s["format"] == "vri-outside-stats" and s["version"] == 1, path
    assert s["renderer"]["name"].startswith(name) and s["renderer"]["version"][0].isdigit(), s["renderer"]
    assert s["timing"]["what"] == "frame" and len(s["timing"]["wall_seconds"]) == 3, s["timing"]
    assert all(t > 0 for t in s["timing"]["wall_seconds"]), s["timing"]
    assert s["image"]["quantisation"] == quantisation, (path, s["image"])
    assert isinstance(s["settings"], dict) and all(isinstance(n, str) and n for n in s["notes"]), path
EOF

# --step overrides the card's step, in voxels; a PNG is 8-bit and says so.
node "$web/three.mjs" small/card.json small/three-step.png small/three-step.json --step 0.25 --frames 1 || fail "three --step"
/usr/bin/python3 -c '
import json, sys
s = json.load(open(sys.argv[1]))
assert s["settings"]["step_voxels"] == 0.25 and s["image"]["quantisation"] == "8-bit", s["settings"]
assert len(s["timing"]["wall_seconds"]) == 1' small/three-step.json || fail "three --step: $(cat small/three-step.json)"

# A card that is not one, and an output it cannot write: one line on stderr, a non-zero exit, nothing written.
sed 's/"vri-scene-card"/"something-else"/' small/card.json > small/bad.json
for adapter in three vtkjs niivue; do
  if node "$web/$adapter.mjs" small/bad.json small/bad.f32 small/bad-stats.json 2> err.txt; then fail "$adapter took a bad card"; fi
  [ "$(wc -l < err.txt)" -eq 1 ] && grep -q "^$adapter: error: .*not a version 1 vri scene card" err.txt || fail "$adapter: $(cat err.txt)"
  [ ! -e small/bad.f32 ] && [ ! -e small/bad-stats.json ] || fail "$adapter wrote output for a bad card"
done
if node "$web/three.mjs" small/card.json small/out.jpg small/out.json 2> err.txt; then fail "three wrote a .jpg"; fi
grep -q "^three: error: .*must end in .f32 or .png" err.txt || fail "three .jpg: $(cat err.txt)"

# Bonsai, the matched scene of paper B, at 80x60.
bonsai=${VRI_DATA_DIR:-$VRI_SOURCE/../shared/data/volumes}/bonsai_256x256x256_uint8.raw
if [ -f "$bonsai" ]; then
  scene bonsai 38 --volume "$bonsai" --tf "$VRI_SOURCE/experiments/tf/paper-b-bonsai.yaml" --size 80x60 \
    --eye 128,190,-340 --target 128,115,128 --up 0,1,0
  # Measured: three.js 0.0124, vtk.js 0.0046, NiiVue 0.049.
  check_adapter bonsai three f32 0.02 perspective
  check_adapter bonsai vtkjs png 0.007 perspective
  check_adapter bonsai niivue png 0.07
else
  echo "no $bonsai: Bonsai not checked"
fi
echo "web peers: all checks passed"
