#!/usr/bin/python3
"""Writes a synthetic N^3 uint8 volume of smooth blobs (scripts/brick-memory.sh, scripts/brick-memory-slurm.sh):
a slab at a time, so that the script holds one slice however large the volume, into PATH.part, then renamed
to PATH. Never committed: `make bricks-memory` and `make bricks-slurm` write it into their scratch folders.

    scripts/blob-volume.py N PATH
"""
import os
import sys

import numpy as np


def main():
    if len(sys.argv) != 3 or not sys.argv[1].isdigit() or not 2 <= int(sys.argv[1]) <= 4096:
        sys.exit("usage: blob-volume.py N PATH (N from 2 to 4096)")
    n, path = int(sys.argv[1]), sys.argv[2]
    axis = (np.arange(n, dtype=np.float32) + 0.5) / n
    y, x = np.meshgrid(axis, axis, indexing="ij")
    with open(path + ".part", "wb") as out:
        for k in range(n):
            z = axis[k]
            v = 0.5 + 0.25 * np.sin(9 * x) * np.cos(7 * y) + 0.25 * np.sin(11 * z + 5 * x * y)
            out.write(np.clip(v * 255, 0, 255).astype(np.uint8).tobytes())
            if k % 256 == 255:
                print(f"blob-volume: {k + 1} of {n} slices", file=sys.stderr)
    os.replace(path + ".part", path)


if __name__ == "__main__":
    main()
