#!/usr/bin/python3
"""VTK's error on Bonsai explained (issue 16, item 3), and VTK against vri timed in the same run.

    tools/peers/decompose_error.py [--bin build/bin] [--out results/peers/decomposition] [--work build/peers-work]
                                   [--rounds 2] [--tables-only]

Every image is compared with vri's exact reference (vri-reference, bound < 1e-7) of paper-b-cpu's Bonsai scene.
Each cause of VTK's error is isolated by a pair of images that differ in that cause alone:
  (a) the transfer function read at ceil(s * 255): vri's exact image with that staircase TF against the exact one
      (and with the staircase at round(s * 255), to confirm which one VTK reads);
  (b) display resampling: VTK's 8-bit frame against its own ray-cast image rounded to 8 bits;
  (c) fixed-point accumulation (with VTK's own sample positions): VTK's 15-bit ray-cast image against vri's
      double composite with the staircase TF, the same step and VTK's early termination;
  (d) early ray termination (VTK stops once the remaining opacity is below 255 / 32768): vri's composite with the
      staircase TF with and without --early-termination 255/32768;
  (e) 8-bit output: the exact image rounded to 8 bits against itself.
The sampling error of the step is the staircase composite against the staircase exact image.
Renders into --work (images and stats, not committed); writes into --out the staircase TFs, decomposition.md,
speed.md and measurements.json. --tables-only rebuilds the tables from the images already in --work.
"""

import argparse
import json
import math
import os
import re
import statistics
import subprocess
import sys

import numpy as np
import OpenImageIO as oiio

SCENE = ["--size", "800x600", "--eye", "128,190,-340", "--target", "128,115,128", "--up", "0,1,0", "--fov", "38"]
VTK_ERT = 255 / 32768  # vtkFixedPointVolumeRayCastHelper: a ray ends once its remaining opacity is below 0xff
STEPS = [2, 0.5, 0.1]


def file_name(label):
    return re.sub("[^A-Za-z0-9.]+", "-", label)


def run(tables_only, words):
    if tables_only:
        return
    print("+ " + " ".join(words), file=sys.stderr, flush=True)
    subprocess.run(words, check=True, stdin=subprocess.DEVNULL)


def load(path):
    return oiio.ImageBuf(path).get_pixels(oiio.FLOAT).astype(np.float64)


def save(path, rgba):
    out = oiio.ImageOutput.create(path)
    out.open(path, oiio.ImageSpec(rgba.shape[1], rgba.shape[0], 4, oiio.FLOAT))
    out.write_image(rgba.astype(np.float32))
    out.close()


def metrics(reference, image):
    """The RMSE of R, G and B pooled (issue 15's RMSE RGB) and of the worst channel, the % of pixels with an error
    above 0.01 and 0.001 in any channel (issue 15's) and in the worst channel (vri-tabulate's), the largest error."""
    error = np.abs(load(image) - load(reference))
    return {"rmse_rgb": float(np.sqrt((error[:, :, :3] ** 2).mean())),
            "rmse": float(np.sqrt((error ** 2).mean(axis=(0, 1))).max()),
            "any_0.01": float((error > 0.01).any(axis=2).mean() * 100),
            "any_0.001": float((error > 0.001).any(axis=2).mean() * 100),
            "above_0.01": float((error > 0.01).mean(axis=(0, 1)).max() * 100),
            "above_0.001": float((error > 0.001).mean(axis=(0, 1)).max() * 100),
            "max": float(error.max())}


def staircase_tf(bin_dir, source, target, rounding):
    """The TF as VTK's 8-bit table reads it: for s in ((k - 1) / 255, k / 255] the value at k / 255 (ceil), or for
    s in [(k - 1/2) / 255, (k + 1/2) / 255) the value at k / 255 (round); vri takes a jump's right-hand value."""
    table = subprocess.run([os.path.join(bin_dir, "vri-tf"), "--samples", "256", "-o", "-", source], check=True,
                           stdout=subprocess.PIPE).stdout.decode().splitlines()[1:]
    value = {}
    for line in table:
        s, r, g, b, tau = (float(v) for v in line.split(",")[:5])
        if abs(s * 255 - round(s * 255)) < 1e-9:
            value[round(s * 255)] = (r, g, b, tau)
    points = []
    for k in range(256):
        lo, hi = ((k - 1) / 255, k / 255) if rounding == "ceil" else ((k - 0.5) / 255, (k + 0.5) / 255)
        lo, hi = max(lo, 0.0), min(hi, 1.0)
        points += [[lo, *value[k]], [hi, *value[k]]]
    with open(target, "w") as f:
        f.write("description: >-\n  %s read as VTK's 8-bit table does, at %s(s * 255): a staircase.\npoints:\n"
                % (os.path.basename(source), rounding))
        for p in points:
            f.write("  - [%r, %r, %r, %r, %r]\n" % tuple(p))


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--bin", default="build/bin")
    p.add_argument("--out", default="results/peers/decomposition")
    p.add_argument("--work", default="build/peers-work")
    p.add_argument("--data", default=os.environ.get("VRI_DATA_DIR", "../shared/data/volumes"))
    p.add_argument("--rounds", type=int, default=2, help="interleaved timing rounds")
    p.add_argument("--tables-only", action="store_true", help="no renders: the tables from the images in --work")
    a = p.parse_args()
    work = a.work
    os.makedirs(work, exist_ok=True)
    os.makedirs(a.out, exist_ok=True)
    tool = lambda name: os.path.join(a.bin, name)
    at = lambda name: os.path.join(work, name)
    tf = "experiments/tf/paper-b-bonsai.yaml"
    volume = ["--volume", os.path.join(a.data, "bonsai_256x256x256_uint8.raw")]
    scene = volume + SCENE + ["-q"]

    for rounding in ("ceil", "round"):  # cheap, and the same each time
        staircase_tf(a.bin, tf, os.path.join(a.out, "tf-bonsai-staircase-%s.yaml" % rounding), rounding)
    stair = os.path.join(a.out, "tf-bonsai-staircase-ceil.yaml")
    run(a.tables_only, [tool("vri-reference"), *scene, "--tf", tf, "-o", at("exact.exr")])
    run(a.tables_only, [tool("vri-reference"), *scene, "--tf", stair, "-o", at("exact-staircase-ceil.exr")])
    run(a.tables_only, [tool("vri-reference"), *scene, "--tf", os.path.join(a.out, "tf-bonsai-staircase-round.yaml"),
         "-o", at("exact-staircase-round.exr")])
    save(at("exact-8bit.exr"), np.round(load(at("exact.exr")) * 255) / 255)

    # Timing, interleaved: VTK's frames shown and vri's methods, in rounds; each run is a median of 3 frames.
    timed = {"VTK d = %g" % d: [tool("vri-peer-vtk"), *scene, "--tf", tf, "--step", str(d), "--repeat", "3"]
             for d in STEPS}
    timed.update({"vri Riemann h = 0.5": [tool("vri-render"), *scene, "--tf", tf, "--step", "0.5", "--repeat", "3"],
                  "vri Riemann h = 0.5 float": [tool("vri-render"), *scene, "--tf", tf, "--step", "0.5",
                                                "--precision", "float", "--repeat", "3"],
                  "vri Riemann h = 0.1": [tool("vri-render"), *scene, "--tf", tf, "--step", "0.1", "--repeat", "3"],
                  "vri Riemann h = 0.25 float": [tool("vri-render"), *scene, "--tf", tf, "--step", "0.25",
                                                 "--precision", "float", "--repeat", "3"],
                  "vri Riemann h = 0.1 float": [tool("vri-render"), *scene, "--tf", tf, "--step", "0.1",
                                                "--precision", "float", "--repeat", "3"],
                  "vri coupled eps = 0.001": [tool("vri-render"), *scene, "--tf", tf, "--method", "coupled",
                                              "--tolerance", "0.001", "--repeat", "3"],
                  "vri exact (1e-7)": [tool("vri-render"), *scene, "--tf", tf, "--method", "exact", "--repeat", "3"]})
    seconds = {label: [] for label in timed}
    for r in range(a.rounds):
        for label, words in timed.items():
            name = file_name(label)
            run(a.tables_only, [*words, "-o", at(name + ".exr"), "--stats", at(name + ".json")])
            if not a.tables_only:
                seconds[label] += json.load(open(at(name + ".json")))["timing"]["wall_seconds"]
    if a.tables_only:
        seconds = json.load(open(os.path.join(a.out, "measurements.json")))["seconds"]

    # The cause images.
    for d in STEPS:
        run(a.tables_only, [tool("vri-peer-vtk"), *scene, "--tf", tf, "--step", str(d), "--image", "raycast",
                            "--repeat", "1", "-o", at("vtk-raycast-d%g.exr" % d)])
        save(at("vtk-raycast-8bit-d%g.exr" % d), np.round(load(at("vtk-raycast-d%g.exr" % d)) * 255) / 255)
        for ert, suffix in ((0, ""), (VTK_ERT, "-ert")):
            run(a.tables_only, [tool("vri-render"), *scene, "--tf", stair, "--method", "composite", "--step", str(d),
                 "--early-termination", repr(ert), "-o", at("composite-staircase-d%g%s.exr" % (d, suffix))])

    rows = [("(a) TF at ceil(s * 255): exact, staircase TF", "exact.exr", "exact-staircase-ceil.exr", None),
            ("(a') TF at round(s * 255), for comparison", "exact.exr", "exact-staircase-round.exr", None),
            ("(e) 8-bit output of the exact image", "exact.exr", "exact-8bit.exr", None)]
    for d in STEPS:
        rows += [("sampling at d: composite vs exact, both staircase", "exact-staircase-ceil.exr",
                  "composite-staircase-d%g.exr" % d, d),
                 ("(d) early termination at 255/32768", "composite-staircase-d%g.exr" % d,
                  "composite-staircase-d%g-ert.exr" % d, d),
                 ("(c) fixed point (VTK ray-cast vs composite, staircase, ERT)", "composite-staircase-d%g-ert.exr" % d,
                  "vtk-raycast-d%g.exr" % d, d),
                 ("(b) display resampling: frame vs ray-cast image in 8 bits", "vtk-raycast-8bit-d%g.exr" % d,
                  file_name("VTK d = %g" % d) + ".exr", d),
                 ("VTK ray-cast image vs exact staircase", "exact-staircase-ceil.exr", "vtk-raycast-d%g.exr" % d, d),
                 ("VTK ray-cast image vs exact", "exact.exr", "vtk-raycast-d%g.exr" % d, d),
                 ("total: VTK's frame vs exact", "exact.exr", file_name("VTK d = %g" % d) + ".exr", d)]
    measured = [(label, d, metrics(at(ref), at(img))) for label, ref, img, d in rows]
    speed = []
    for label in timed:
        name = file_name(label)
        speed.append((label, statistics.median(seconds[label]), len(seconds[label]),
                      metrics(at("exact.exr"), at(name + ".exr"))))
    with open(os.path.join(a.out, "measurements.json"), "w") as f:
        json.dump({"decomposition": measured, "speed": speed, "seconds": seconds}, f, indent=1)

    columns = ("| RMSE RGB | RMSE worst | % px > 0.01 | % px > 0.001 | worst % > 0.001 | max |")
    cells = lambda m: "| %.5f | %.5f | %.1f | %.1f | %.1f | %.4f |" % (
        m["rmse_rgb"], m["rmse"], m["any_0.01"], m["any_0.001"], m["above_0.001"], m["max"])
    with open(os.path.join(a.out, "decomposition.md"), "w") as f:
        f.write("| cause | d | share of VTK's RGB MSE " + columns + "\n|---|--:|--:|--:|--:|--:|--:|--:|--:|\n")
        totals = {d: m["rmse_rgb"] ** 2 for label, d, m in measured if label.startswith("total")}
        for label, d, m in measured:
            total = totals.get(d, totals[0.5])  # the causes without a step: against VTK at d = 0.5
            f.write("| %s | %s | %.0f %% %s\n" % (label, "-" if d is None else "%g" % d,
                                                 100 * m["rmse_rgb"] ** 2 / total, cells(m)))
    with open(os.path.join(a.out, "speed.md"), "w") as f:
        f.write("| renderer | s/frame (median) | frames " + columns + "\n|---|--:|--:|--:|--:|--:|--:|--:|--:|\n")
        for label, s, n, m in speed:
            f.write("| %s | %.3f | %d %s\n" % (label, s, n, cells(m)))

if __name__ == "__main__":
    main()
