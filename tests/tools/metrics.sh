#!/usr/bin/env bash
# vri-diff's image metrics and masks against a direct NumPy computation of their definitions
# (libvri/core/image_metrics.h, pixel_mask.h): PSNR (peak 1), SSIM (Wang et al. 2004: 11 x 11 Gaussian window,
# sigma 1.5, K1 0.01, K2 0.03, valid windows, each channel alone), relative MSE and SMAPE (epsilon 0.01), over
# all pixels and over the hit, alpha>T and image masks; the masks also change the % of rays above each
# threshold as counted by hand.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
bin=${VRI_BIN:?}
python=/usr/bin/python3
"$python" -c 'import numpy, OpenImageIO' 2> /dev/null || { echo "needs python3-numpy and python3-openimageio: skipping"; exit 77; }

"$python" - <<'PY'
import numpy as np, OpenImageIO as oiio
rng = np.random.default_rng(7)
h, w = 30, 40
y, x = np.mgrid[0:h, 0:w]
blob = np.exp(-((x - 22.0) ** 2 + (y - 14.0) ** 2) / 60.0)
a = np.zeros((h, w, 4), np.float32)
for c, k in enumerate((0.9, 0.6, 0.3)):
    a[..., c] = k * blob
a[..., 3] = np.where(blob > 0.05, blob, 0.0)           # a plume on an empty background
b = a + rng.normal(0, 0.02, a.shape).astype(np.float32) * (a[..., 3:4] > 0)
mask = np.zeros((h, w, 1), np.float32); mask[5:20, 10:30] = 1
for name, img in (("a.exr", a), ("b.exr", b), ("mask.exr", mask)):
    out = oiio.ImageOutput.create(name)
    out.open(name, oiio.ImageSpec(w, h, img.shape[2], "float"))
    out.write_image(np.ascontiguousarray(img)); out.close()
PY
for m in all hit 'alpha>0.3' mask.exr; do
  "$bin/vri-diff" a.exr b.exr --mask "$m" --threshold 0.01,0.03 --failpercent 100 --warnpercent 100 --json "m-${m//[>.]/_}.json" > /dev/null ||
    fail "vri-diff --mask $m failed"
done
"$python" - <<'PY' || fail "the metrics differ from NumPy's"
import json, numpy as np, OpenImageIO as oiio
from numpy.lib.stride_tricks import sliding_window_view as windows
a, b, mask_image = (oiio.ImageBuf(p).get_pixels(oiio.FLOAT).astype(np.float64) for p in ("a.exr", "b.exr", "mask.exr"))
g = np.exp(-((np.arange(11) - 5.0) ** 2) / (2 * 1.5 ** 2)); g /= g.sum(); g2 = np.outer(g, g)
def blur(z):  # valid 2D Gaussian means, directly (no separation)
    return np.einsum("ijkl,kl->ij", windows(z, (11, 11)), g2)
def ssim_map(p, q):
    mp, mq = blur(p), blur(q)
    vp, vq, cpq = blur(p * p) - mp * mp, blur(q * q) - mq * mq, blur(p * q) - mp * mq
    c1, c2 = 0.01 ** 2, 0.03 ** 2
    return ((2 * mp * mq + c1) * (2 * cpq + c2)) / ((mp * mp + mq * mq + c1) * (vp + vq + c2))
masks = {
    "all": np.ones(a.shape[:2], bool),
    "hit": (a[..., 3] > 0) | (b[..., 3] > 0),
    "alpha_0_3": (a[..., 3] > 0.3) | (b[..., 3] > 0.3),
    "mask_exr": mask_image[..., 0] != 0,
}
for name, keep in masks.items():
    r = json.load(open(f"m-{name}.json"))
    assert r["pixels"] == keep.sum(), (name, r["pixels"], keep.sum())
    e = np.abs(a - b)[keep]                       # (pixels, channels)
    centres = keep[5:-5, 5:-5]
    for c, ch in enumerate(r["metrics"]["channels"]):
        mse = np.mean(e[:, c] ** 2)
        psnr = 10 * np.log10(1 / mse) if mse > 0 else None
        ssim = ssim_map(a[..., c], b[..., c])[centres].mean()
        rel = np.mean(e[:, c] ** 2 / (a[..., c][keep] ** 2 + 0.01))
        smape = np.mean(e[:, c] / (np.abs(a[..., c][keep]) + np.abs(b[..., c][keep]) + 0.01))
        if psnr is None:
            assert ch["psnr_db"] is None, ch
        else:
            assert abs(ch["psnr_db"] - psnr) < 1e-9, (name, c, ch["psnr_db"], psnr)
        assert abs(ch["ssim"] - ssim) < 1e-9, (name, c, ch["ssim"], ssim)
        assert abs(ch["rel_mse"] - rel) < 1e-12 and abs(ch["smape"] - smape) < 1e-12, (name, c, ch)
        for t, above in zip((0.01, 0.03), r["channels"][c]["above"]):
            assert above["count"] == np.count_nonzero(e[:, c] > t), (name, c, t, above)
            assert abs(above["percent"] - 100 * np.count_nonzero(e[:, c] > t) / keep.sum()) < 1e-9
    assert abs(r["metrics"]["all"]["psnr_db"] - 10 * np.log10(1 / np.mean(e ** 2))) < 1e-9, name
    assert r["metrics"]["ssim_windows"] == centres.sum(), name
# The mask changes the percentages as it should: the plume's errors over fewer pixels read larger.
p_all = json.load(open("m-all.json"))["channels"][0]["above"][0]["percent"]
p_hit = json.load(open("m-hit.json"))["channels"][0]["above"][0]["percent"]
assert p_hit > 2 * p_all, (p_all, p_hit)
assert json.load(open("m-hit.json"))["pixels_counted"].startswith("the pixels the volume covers"), "the JSON does not say which pixels"
PY
"$bin/vri-diff" a.exr b.exr --mask hit --failpercent 100 --warnpercent 100 | grep -q "^PSNR [0-9.]* dB (peak 1), SSIM 0\.[0-9]* " || fail "the summary has no metrics line"
# In an experiment: a comparison's mask reaches vri-diff, and its table says which pixels it counts.
cat > tf.yaml <<'YAML'
points:
  - [0.0, 0.0, 0.0, 0.0, 0.0]
  - [0.4, 0.0, 0.0, 0.0, 0.0]
  - [0.6, 0.9, 0.5, 0.2, 3.0]
  - [1.0, 0.2, 0.4, 1.0, 1.0]
YAML
cat > exp.yaml <<'YAML'
name: masked
title: A masked comparison
paper: {paper: none, item: masks, says: a test}
scenes:
  cube: {field: linear, field_dims: [6, 6, 6], convention: node, tf: tf.yaml, size: [48, 36], camera: {eye: [3.2, 2.1, 4.5], target: [0, 0, 0], up: [0, 1, 0], fov: 40}}
references:
  fine: {method: riemann, step: 0.05}
methods:
  coarse: {method: riemann, step: [1, 0.5]}
comparisons:
  all: {reference: fine}
  hit: {reference: fine, mask: hit}
tables:
  masked: {title: "over the covered pixels", comparisons: [hit]}
YAML
"$bin/vri-run" --results res exp.yaml 2> run.txt || { cat run.txt; fail "the masked experiment failed"; }
grep -q "Percentage of rays (the pixels the volume covers in either image, alpha > 0)" res/masked/masked.md ||
  fail "the table does not say which pixels: $(cat res/masked/masked.md)"
"$python" - res/masked/all-coarse-h1.json res/masked/hit-coarse-h1.json <<'PY' || fail "the mask did not reach vri-diff"
import json, sys
everything, hit = (json.load(open(p)) for p in sys.argv[1:])
assert hit["pixels"] < everything["pixels"] == 48 * 36, (hit["pixels"], everything["pixels"])
assert hit["channels"][0]["above"][0]["percent"] > everything["channels"][0]["above"][0]["percent"]
PY
sed 's/mask: hit/mask: alpha>7/' exp.yaml > bad.yaml
if "$bin/vri-run" --results res2 --dry-run bad.yaml 2> bad.txt > /dev/null; then fail "a bad mask was taken"; fi
grep -q "mask: 'alpha>7': expected alpha>T with T a number in \[0, 1)" bad.txt || fail "the bad mask's message: $(cat bad.txt)"
# Non-finite pixels: vri-diff warns, names how they were counted and records how many; FLIP, which needs finite
# colours, says why it is missing.
"$python" - <<'PY'
import numpy as np, OpenImageIO as oiio
a = np.full((6, 8, 4), 0.5, np.float32)
a[2, 3, 0] = np.nan; a[4, 5, 1] = np.inf
out = oiio.ImageOutput.create("nan.exr"); out.open("nan.exr", oiio.ImageSpec(8, 6, 4, "float")); out.write_image(a); out.close()
a[2, 3, 0] = 0.5; a[4, 5, 1] = 0.5
out = oiio.ImageOutput.create("grey.exr"); out.open("grey.exr", oiio.ImageSpec(8, 6, 4, "float")); out.write_image(a); out.close()
PY
rc=0
"$bin/vri-diff" grey.exr nan.exr --json nan.json > nan.txt 2> nan-err.txt || rc=$?
[ "$rc" -eq 3 ] || fail "NaN against a number: exit $rc, expected 3 (failure)"
grep -q "^vri-diff: warning: B: 2 of 48 pixels are not finite (first at 3,2: R=nan G=0.5 B=0.5 A=0.5); each against a number counts as an infinite error, equal ones as none$" nan-err.txt ||
  fail "the non-finite warning: $(cat nan-err.txt)"
"$python" - <<'PY' || fail "the non-finite record: $(cat nan.json)"
import json
d = json.load(open("nan.json"))
assert d["nonfinite_pixels"] == {"a": 0, "b": 2}, d["nonfinite_pixels"]
assert d["metrics"]["flip"]["ldr"] is None and "finite" in d["metrics"]["flip"]["unavailable"], d["metrics"]["flip"]
PY
echo "metrics: PSNR, SSIM, relative MSE and SMAPE equal NumPy's over four masks; a masked comparison's table says so"
