#!/usr/bin/env bash
# The results viewer (docs/results-viewer.md): vri-run --gallery writes results/index.html, a page per
# experiment and each render's float data (viewer-data/<id>.js, from its EXR); opened from the file system in
# headless Chromium (no server, no flag that lets a page read files), the page loads without a console error,
# picks two renders, shows each one's float values under the mouse exactly as the EXR holds them, and draws
# every view: A, B, side by side, swipe, flip and the error map. The screenshot of A shows the probed pixel in
# the PNG preview's colour; B's and the error map's differ from A's. A hostile title reaches the page as text.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
web=$VRI_SOURCE/tools/peers/web
[ -x /usr/bin/chromium ] || { echo "no /usr/bin/chromium (make deps installs it): skipping"; exit 77; }
command -v node >/dev/null || { echo "no node: skipping"; exit 77; }
[ -d "$web/node_modules/playwright-core" ] || { echo "no $web/node_modules (make deps runs npm ci there): skipping"; exit 77; }
/usr/bin/python3 -c 'import numpy, OpenImageIO' 2>/dev/null || { echo "python3-numpy or python3-openimageio not installed: skipping"; exit 77; }

cat > tf.yaml <<'YAML'
points:
  - [0.0, 0.0, 0.0, 0.0, 0.0]
  - [1.0, 1.0, 0.6, 0.2, 0.8]
YAML
cat > exp.yaml <<'YAML'
name: view
title: 'A view of "two" runs </script><script>document.title="pwned"</script> & more'
paper: {paper: none, item: none, says: a test}
scenes:
  s: {field: linear, field_dims: [5, 5, 5], convention: node, tf: tf.yaml, size: [40, 30]}
methods:
  riemann: {step: [1, 0.25]}
comparisons:
  vs-fine: {reference: riemann-h0.25, runs: [riemann-h1], diff_image: png}
YAML
"$VRI_BIN/vri-run" --results out --gallery out exp.yaml 2> run.txt || fail "the run failed: $(cat run.txt)"
grep -q "wrote the viewer, out/index.html, and the float data of 2 renders" run.txt || fail "vri-run's line: $(cat run.txt)"
for f in out/index.html out/view/index.html out/viewer/vri-viewer.js out/viewer/vri-viewer.css \
         out/view/viewer-data/riemann-h1.js out/view/viewer-data/riemann-h0.25.js; do
  [ -s "$f" ] || fail "$f was not written"
done
cmp out/viewer/vri-viewer.js "$VRI_SOURCE/tools/viewer/vri-viewer.js" || fail "the viewer's script is not tools/viewer's"
# The title is data, never markup: no '<' of it reaches the HTML but the <title>'s escaped one.
! grep -q '<script>document' out/view/index.html || fail "the title's markup reached the page: $(grep -o '.\{20\}<script>document.\{20\}' out/view/index.html)"

grep -q '<p id="vri-fallback">This page is drawn by \.\./viewer/vri-viewer\.js, which did not run' out/view/index.html ||
  fail "the page has no sentence for a browser that does not run its script"

x=21 y=13
node "$VRI_SOURCE/tests/tools/lib/viewer_check.mjs" out/view/index.html riemann-h1 riemann-h0.25 $x $y shots > seen.json 2> check.txt ||
  fail "the browser check: $(cat check.txt)"
/usr/bin/python3 - "$x" "$y" <<'PYEOF' || fail "what the page showed"
import json, sys, numpy as np, OpenImageIO as oiio
x, y = int(sys.argv[1]), int(sys.argv[2])
seen = json.load(open("seen.json"))
def exr(path):
    inp = oiio.ImageInput.open(path); img = inp.read_image(oiio.FLOAT); inp.close(); return img
a, b = exr("out/view/riemann-h1.exr"), exr("out/view/riemann-h0.25.exr")
if seen["consoleErrors"]:
    sys.exit(f"console errors: {seen['consoleErrors']}")
# The probe's values are the EXR's, float32 for float32.
for name, img in (("a", a), ("b", b)):
    shown = np.array(seen[name], dtype=np.float32)
    if not np.array_equal(shown, img[y, x]):
        sys.exit(f"{name}: the page shows {seen[name]} at ({x},{y}), the EXR holds {img[y, x].tolist()}")
want = np.abs(a[y, x].astype(np.float64) - b[y, x].astype(np.float64))
if not np.allclose(np.array(seen["error"], dtype=np.float64), want, rtol=1e-6, atol=1e-9):
    sys.exit(f"error: the page shows {seen['error']}, |A - B| is {want.tolist()}")
# Screenshot of A: the probed pixel's block in the preview's colour (sRGB of the premultiplied colour on black).
def srgb(v):
    v = min(max(float(v), 0.0), 1.0)
    return round(255 * (v * 12.92 if v <= 0.0031308 else 1.055 * v ** (1 / 2.4) - 0.055))
def shot(mode):
    inp = oiio.ImageInput.open(seen["screenshots"][mode]); img = inp.read_image(oiio.UINT8); inp.close(); return img
p = seen["points"]["a"]
got = shot("a")[int(p["y"]), int(p["x"]), :3].astype(int)
exp = np.array([srgb(c) for c in a[y, x, :3]])
if np.abs(got - exp).max() > 1:
    sys.exit(f"the A view shows {got.tolist()} at the probed pixel, the preview's colour is {exp.tolist()}")
# Every view drew something of its own: B differs from A, the error map from both, and no view is one colour.
views = {m: shot(m)[..., :3] for m in ("a", "b", "side-by-side", "swipe", "flip", "error")}
for m, img in views.items():
    if img.reshape(-1, 3).std(axis=0).max() < 1:
        sys.exit(f"the {m} view is one colour")
for m in ("b", "error"):
    if np.array_equal(views[m], views["a"]):
        sys.exit(f"the {m} view is the A view")
if seen["index"] is None:
    sys.exit("the index page was not checked")
PYEOF
echo "viewer checks passed"
