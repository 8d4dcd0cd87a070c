#!/usr/bin/env bash
# vri-diff --channels (an RGB image, as many renderers write, against vri's RGBA) and the hint a failed
# comparison gives when B is A upside down.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
bin=${VRI_BIN:?}
python=/usr/bin/python3
"$python" -c 'import numpy, OpenImageIO' 2> /dev/null || { echo "needs python3-numpy and python3-openimageio: skipping"; exit 77; }
source "$(dirname "${BASH_SOURCE[0]}")/lib/blob.sh" && write_blob_scene
"$bin/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 32x24 -q -o a.exr
"$python" - <<'PY'
import numpy as np, OpenImageIO as oiio
image = oiio.ImageBuf("a.exr").get_pixels(oiio.FLOAT)
def write(name, pixels, channels):
    spec = oiio.ImageSpec(pixels.shape[1], pixels.shape[0], len(channels), "float")
    spec.channelnames = channels
    out = oiio.ImageOutput.create(name)
    assert out.open(name, spec) and out.write_image(np.ascontiguousarray(pixels)) and out.close()
write("rgb.exr", image[..., :3], ("R", "G", "B"))
write("flipped.exr", image[::-1], ("R", "G", "B", "A"))
PY
set +e
"$bin/vri-diff" a.exr rgb.exr > /dev/null 2> shape.txt; rc=$?
set -e
[ "$rc" -eq 4 ] || fail "RGB against RGBA without --channels: exit $rc, expected 4 (shapes differ)"
"$bin/vri-diff" a.exr rgb.exr --channels R,G,B --fail 0 > out.txt || fail "--channels R,G,B: the same colours differ"
set +e
"$bin/vri-diff" a.exr rgb.exr --channels R,G,B,A > /dev/null 2> err.txt; rc=$?
set -e
[ "$rc" -eq 1 ] && grep -q "rgb.exr: no channel 'A' (it has R,G,B)" err.txt || fail "--channels A on an RGB image: $(cat err.txt)"
set +e
"$bin/vri-diff" a.exr flipped.exr --fail 0.01 > /dev/null 2> hint.txt; rc=$?
set -e
[ "$rc" -eq 3 ] || fail "the flipped image passed (exit $rc)"
grep -q "^vri-diff: hint: B flipped vertically is .* times nearer A .*is B's row 0 at the bottom?" hint.txt ||
  fail "no flip hint: $(cat hint.txt)"
"$bin/vri-diff" a.exr a.exr --fail 0 > /dev/null 2> none.txt && [ ! -s none.txt ] || fail "a hint for equal images"
echo "vri-diff: --channels and the flip hint"
