#!/usr/bin/python3
"""Writes a large, mostly empty uint8 volume as a vri .vdb without ever holding its dense box: small
pieces (a procedural cloud, or a raw volume such as the Bonsai) placed in an empty box of BOX^3 voxels.
Needs Debian's python3-openvdb and python3-numpy, and vri-convert (for the metadata vri reads back).

  scripts/sparse-scene.py cloud.vdb --box 1024 --pieces 4
  scripts/sparse-scene.py bonsai2048.vdb --box 2048 --volume bonsai_256x256x256_uint8.raw --pieces 8

Piece k sits at an offset spread along the box's diagonal (the first one in the middle when there is
one). The cloud is a sum of Gaussian blobs in a 96^3 block, scaled to 0..255, deterministic.
"""
import argparse
import os
import subprocess
import sys
import tempfile

import numpy as np
import pyopenvdb as vdb


def cloud(n=96, blobs=24):
    rng = np.random.default_rng(7)
    z, y, x = np.mgrid[0:n, 0:n, 0:n].astype(np.float32) / n
    field = np.zeros((n, n, n), np.float32)
    for _ in range(blobs):
        c = rng.uniform(0.25, 0.75, 3)
        r = rng.uniform(0.06, 0.16)
        field += np.exp(-((x - c[0]) ** 2 + (y - c[1]) ** 2 + (z - c[2]) ** 2) / (2 * r * r))
    field *= 255.0 / field.max()
    return np.where(field > 8, field, 0).astype(np.uint8)  # (z, y, x), zero outside the cloud


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("output", help="the .vdb to write")
    ap.add_argument("--box", type=int, required=True, help="voxels along each axis of the empty box")
    ap.add_argument("--volume", help="a raw uint8 piece NAME_XxYxZ_uint8.raw (default: the procedural cloud)")
    ap.add_argument("--pieces", type=int, default=1, help="copies of the piece placed in the box")
    ap.add_argument("--vri-convert", default=os.path.join(os.environ.get("VRI_BIN", "build/bin"), "vri-convert"))
    args = ap.parse_args()

    if args.volume:
        dims = [int(d) for d in os.path.basename(args.volume).rsplit("_", 2)[1].split("x")]
        piece = np.fromfile(args.volume, np.uint8).reshape(dims[2], dims[1], dims[0])
    else:
        piece = cloud()
    size = np.array(piece.shape[::-1])  # x, y, z
    if args.pieces < 1 or (size > args.box).any():
        sys.exit(f"sparse-scene.py: {args.pieces} pieces of {size.tolist()} do not fit a box of {args.box}")

    # vri's metadata (type, format version, transform to voxel centres) from a 1-voxel volume vri writes.
    with tempfile.TemporaryDirectory() as tmp:
        raw = os.path.join(tmp, "seed_1x1x1_uint8.raw")
        np.zeros(1, np.uint8).tofile(raw)
        subprocess.run([args.vri_convert, "-q", raw, os.path.join(tmp, "seed.vdb")], check=True)
        grid = vdb.read(os.path.join(tmp, "seed.vdb"), "density")
    grid.metadata = {**grid.metadata, "vri_dims": (args.box, args.box, args.box)}
    spare = args.box - size
    for k in range(args.pieces):
        t = 0.5 if args.pieces == 1 else k / (args.pieces - 1)
        offset = tuple(int(v) for v in np.round(spare * t))
        # OpenVDB's arrays are indexed [x][y][z]; values equal to the background 0 stay inactive.
        grid.copyFromArray(np.ascontiguousarray(piece.transpose(2, 1, 0)).astype(np.float32), ijk=offset, tolerance=0)
    vdb.write(args.output, grids=[grid])
    print(f"{args.output}: {args.box}^3 box, {args.pieces} pieces of {size.tolist()}, "
          f"{grid.activeVoxelCount()} active voxels, {os.path.getsize(args.output)} bytes")


if __name__ == "__main__":
    main()
