#!/usr/bin/python3
"""A volume renderer that reads nothing but a vri scene card: the template for checking your own.

    vri-render --volume V --tf TF --method riemann --step 0.5 --precision double \\
               --describe card.json --describe-voxels voxels.raw
    python3 render_from_card.py card.json image.exr      (or image.f32, raw float32 RGBA, or image.npy)
    vri-diff vri.exr image.exr --fail 0

It follows docs/scene-card.md line by line: every formula below is one the card states in words, and
every number comes from the card. NumPy only (OpenImageIO to write EXR when asked). It renders the
fixed-step methods (riemann, composite) in double precision, the precision in which it reproduces
vri-render's image: bit for bit where NumPy's exp agrees with the C library's (the test checks it,
tests/tools/scene_card.sh), else within a unit in the last place of a float32 channel.

The evaluation order is vri's (a + b + c is (a + b) + c), since floating point is not associative: a
renderer that only needs to be within an error tolerance may write these formulas any way it likes.
"""
import json
import math
import os
import sys

import numpy as np

VOXEL_TYPES = {"uint8": "<u1", "uint16": "<u2", "float32": "<f4"}


def load_card(path):
    with open(path, encoding="utf-8") as f:
        card = json.load(f)
    if card.get("format") != "vri-scene-card" or card.get("version") != 1:
        sys.exit(f"{path}: not a version 1 vri scene card")
    return card


class Scalar:
    """s at texture coordinates u (card: volume.*)."""

    def __init__(self, card, card_dir):
        volume = card["volume"]
        self.analytic = volume["kind"] == "analytic"
        if self.analytic:
            return  # s = u.x exactly (volume.field.formula)
        dims = volume["dims"]
        voxels = volume["voxels"]
        raw = np.fromfile(os.path.join(card_dir, voxels["file"]), dtype=VOXEL_TYPES[voxels["voxel_type"]])
        # x fastest: index x + nx (y + ny z), so the array reads [z, y, x]; flattened again for gathers.
        self.voxels = raw.astype(np.float64)
        self.dims = np.array(dims, dtype=np.int64)
        self.stride = np.array([1, dims[0], dims[0] * dims[1]], dtype=np.int64)
        self.stride[self.dims == 1] = 0  # an axis of one voxel reads it twice
        index = volume["voxel_index_from_texture"]
        self.scale = np.array(index["scale"])
        self.offset = np.array(index["offset"])
        self.max_coord = (self.dims - 1).astype(np.float64)
        self.max_base = np.maximum(self.dims - 2, 0)
        self.lo = volume["value_to_s"]["lo"]
        self.inverse_range = volume["value_to_s"]["inverse_range"]

    def __call__(self, u):  # u: (n, 3)
        if self.analytic:
            return u[:, 0].copy()
        x = np.clip(u * self.scale - self.offset, 0.0, self.max_coord)  # continuous voxel index, clamped
        i = np.minimum(x.astype(np.int64), self.max_base)  # x >= 0, so truncation is floor
        w = x - i
        base = i @ self.stride
        sx, sy, sz = self.stride
        v = lambda o: self.voxels[base + o]
        lerp = lambda a, b, t: a + t * (b - a)
        c00 = lerp(v(0), v(sx), w[:, 0])
        c10 = lerp(v(sy), v(sy + sx), w[:, 0])
        c01 = lerp(v(sz), v(sz + sx), w[:, 0])
        c11 = lerp(v(sz + sy), v(sz + sy + sx), w[:, 0])
        c0 = lerp(c00, c10, w[:, 1])
        c1 = lerp(c01, c11, w[:, 1])
        return (lerp(c0, c1, w[:, 2]) - self.lo) * self.inverse_range


class TransferFunction:
    """(r, g, b, tau) at s (card: transfer_function.*)."""

    def __init__(self, card):
        points = card["transfer_function"]["points"]
        self.s = np.array([p["s"] for p in points])
        self.values = np.array([[p["r"], p["g"], p["b"], p["tau"]] for p in points])

    def __call__(self, s):
        n = len(self.s)
        # The bracket s[i] <= s < s[i + 1] (at equal s, a jump, the right point wins); constant outside.
        i = np.clip(np.searchsorted(self.s, s, side="right") - 1, 0, max(n - 2, 0))
        if n == 1:
            return np.repeat(self.values[:1], len(s), axis=0)
        a, b = self.values[i], self.values[i + 1]
        w = (s - self.s[i]) / (self.s[i + 1] - self.s[i])
        out = a + w[:, None] * (b - a)
        out[~(s >= self.s[0])] = self.values[0]  # NaN included, as vri
        out[~(s < self.s[-1])] = self.values[-1]
        return out


def normalize(v):
    length_squared = v[:, 0] * v[:, 0] + v[:, 1] * v[:, 1] + v[:, 2] * v[:, 2]
    return v * (1.0 / np.sqrt(length_squared))[:, None]


def length(v):
    return np.sqrt(v[:, 0] * v[:, 0] + v[:, 1] * v[:, 1] + v[:, 2] * v[:, 2])


def rays(card):
    """Every pixel's unit direction, row 0 at the top (card: camera.ray)."""
    cam = card["camera"]
    width, height, zoom = cam["width"], cam["height"], cam["zoom"]
    cx, cy = cam["zoom_centre_pixels"]
    j, i = np.mgrid[0:height, 0:width]
    fx = cx + (i.ravel() + 0.5 - 0.5 * width) / zoom
    fy = cy + (j.ravel() + 0.5 - 0.5 * height) / zoom
    x = (2.0 * fx / width - 1.0) * cam["tan_half_fov_x"]
    y = (1.0 - 2.0 * fy / height) * cam["tan_half_fov_y"]
    basis = cam["basis"]
    forward, right, up = (np.array(basis[k]) for k in ("forward", "right", "up"))
    return normalize(forward + x[:, None] * right + y[:, None] * up)


def clip(eye, d, lo, hi):
    """[t_near, t_far] of eye + t d inside the closed box, t_near >= 0 (card: integration.domain)."""
    n = len(d)
    t_near, t_far = np.zeros(n), np.full(n, np.inf)
    hit = np.ones(n, dtype=bool)
    with np.errstate(divide="ignore", invalid="ignore"):
        for a in range(3):
            parallel = d[:, a] == 0.0
            hit &= ~(parallel & ((eye[a] < lo[a]) | (eye[a] > hi[a])))
            t0 = (lo[a] - eye[a]) / d[:, a]
            t1 = (hi[a] - eye[a]) / d[:, a]
            t0, t1 = np.minimum(t0, t1), np.maximum(t0, t1)
            t_near = np.where(parallel, t_near, np.maximum(t_near, t0))
            t_far = np.where(parallel, t_far, np.minimum(t_far, t1))
    return t_near, t_far, hit & (t_near <= t_far)


def mix(x):
    """Wellons' lowbias32 on uint32 arrays (card: method.jitter.fraction); NumPy's uint32 products wrap."""
    x = x ^ (x >> np.uint32(16))
    x = x * np.uint32(0x7FEB352D)
    x = x ^ (x >> np.uint32(15))
    x = x * np.uint32(0x846CA68B)
    return x ^ (x >> np.uint32(16))


def jitter_fraction(card, seed):
    """Each pixel's first-sample fraction in [0, 1) under `seed`, in the rays' order (row 0 first)."""
    cam = card["camera"]
    py, px = (a.ravel().astype(np.uint32) for a in np.mgrid[0:cam["height"], 0:cam["width"]])
    h = mix(px ^ mix(py ^ mix(np.full(px.shape, seed, dtype=np.uint32))))
    return (h >> np.uint32(8)).astype(np.float64) * 2.0**-24


def schedule(method, entry, exit_, eye_u, dims, fraction=None):
    """Paper A's placement: t_start, t_incr, count, t_end (card: method.placements); with a jitter
    `fraction`, the first sample at that fraction of the step (card: method.jitter.t_start)."""
    placement, rate = method["placement"], method["samples_per_voxel"]
    ray = exit_ - entry
    t_end = length(ray)
    if placement == "entry-exit-corner":
        samples = np.ceil(rate * length(ray * (dims - 1.0)))
    elif placement == "entry-exit":
        samples = np.floor(length(ray * dims) * rate)
    else:
        samples = length(ray * dims) * rate
    ok = (t_end > 0) & (samples > 0) & np.isfinite(samples)
    with np.errstate(divide="ignore", invalid="ignore"):
        t_incr = np.where(ok, t_end / samples, 0.0)
        if placement == "eye":
            steps = length(entry - eye_u) / t_incr
            t_start = (1.0 - (steps - np.floor(steps))) * t_incr
        else:
            t_start = 0.5 * t_incr
    if fraction is not None:
        t_start = fraction * t_incr
    if placement in ("entry-exit", "entry-exit-corner") and fraction is None:
        count = np.where(ok, samples, 0).astype(np.int64)
    else:  # every k with t_start + k t_incr < t_end, counted on those very numbers
        with np.errstate(divide="ignore", invalid="ignore"):
            count = np.where(ok & (t_start < t_end), np.ceil((t_end - t_start) / t_incr), 0).astype(np.int64)
        for _ in range(4):
            count -= (count > 0) & ~(t_start + (count - 1) * t_incr < t_end)
            count += ok & (t_start + count * t_incr < t_end)
    return t_start, t_incr, np.where(ok, count, 0), t_end


def render(card, card_dir):
    """The card's image: one frame, or with jitter the mean of its frames (card: method.jitter.frames_rule)."""
    jitter = card["method"].get("jitter")
    if not jitter:
        return render_frame(card, card_dir, None)
    total = np.zeros((card["camera"]["height"], card["camera"]["width"], 4))
    for f in range(jitter["frames"]):
        seed = (jitter["seed"] + f) % 2**32
        total += render_frame(card, card_dir, jitter_fraction(card, seed))  # float32 values, summed in double
    return (total / jitter["frames"]).astype(np.float32)


def render_frame(card, card_dir, fraction):
    method = card["method"]
    if method["kind"] != "fixed-step" or method["settings"]["method"] not in ("riemann", "composite"):
        sys.exit("this example renders the fixed-step riemann and composite methods only")
    composite = method["settings"]["method"] == "composite"
    colour_times_tau = card["transfer_function"]["emission"] == "color-times-extinction"
    cam, box = card["camera"], card["volume"]["box"]
    eye, lo, hi = np.array(cam["eye"]), np.array(box["lo"]), np.array(box["hi"])
    scalar, tf = Scalar(card, card_dir), TransferFunction(card)

    d = rays(card)
    t_near, t_far, hit = clip(eye, d, lo, hi)
    t_near, t_far = np.where(hit, t_near, 0.0), np.where(hit, t_far, 0.0)
    entry = (eye + t_near[:, None] * d - lo) / (hi - lo)  # texture coordinates
    exit_ = (eye + t_far[:, None] * d - lo) / (hi - lo)
    dims = np.array(method["dims_for_placement"])
    t_start, t_incr, count, t_end = schedule(method, entry, exit_, (eye - lo) / (hi - lo), dims, fraction)
    count = np.where(hit, count, 0)
    with np.errstate(divide="ignore", invalid="ignore"):
        du = np.where((count > 0)[:, None], (exit_ - entry) / t_end[:, None], 0.0)
        dx = np.where(count > 0, t_incr * ((t_far - t_near) / t_end), 0.0)

    colour = np.zeros((len(d), 3))
    transparency = np.ones(len(d))
    for k in range(int(count.max(initial=0))):  # all rays at their k-th sample at once
        live = np.nonzero(k < count)[0]
        u = entry[live] + (t_start[live] + float(k) * t_incr[live])[:, None] * du[live]
        v = tf(scalar(u))
        tau, h = v[:, 3], dx[live]
        attenuation = np.exp(-tau * h)
        if composite:
            alpha = -np.expm1(-tau * h)
            with np.errstate(divide="ignore", invalid="ignore"):
                weight = alpha if colour_times_tau else np.where(tau > 0, alpha / tau, h)
        else:
            weight = tau * h if colour_times_tau else h
        w = transparency[live] * weight
        colour[live] += w[:, None] * v[:, :3]
        transparency[live] *= attenuation

    image = np.empty((len(d), 4), dtype=np.float32)  # premultiplied, linear, (0, 0, 0, 0) background
    image[:, :3] = colour
    image[:, 3] = 1.0 - transparency
    return image.reshape(cam["height"], cam["width"], 4)


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: render_from_card.py CARD.json OUT.exr|OUT.f32|OUT.npy")
    card_path, out = sys.argv[1:]
    image = render(load_card(card_path), os.path.dirname(os.path.abspath(card_path)))
    if out.endswith(".npy"):
        np.save(out, image)
    elif out.endswith(".f32"):  # raw little-endian float32 RGBA, row 0 at the top (docs/outside-renderers.md)
        image.astype("<f4").tofile(out)
    else:
        import OpenImageIO as oiio  # Debian's python3-openimageio
        spec = oiio.ImageSpec(image.shape[1], image.shape[0], 4, "float")
        spec.channelnames = ("R", "G", "B", "A")
        writer = oiio.ImageOutput.create(out)
        if not writer or not writer.open(out, spec) or not writer.write_image(image) or not writer.close():
            sys.exit(f"{out}: cannot write: {oiio.geterror()}")
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
