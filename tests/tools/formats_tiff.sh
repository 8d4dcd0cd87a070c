#!/usr/bin/env bash
# TIFF stacks: single-page TIFFs written by a few lines of Python (baseline TIFF, no library), joined into
# one multi-page file by libtiff's tiffcp, read by vri-convert with each page a z slice and each row a y.
# uint16 pages are kept; int16 pages become float32 with the int16 range (stored_voxels.h).
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
python=/usr/bin/python3
command -v tiffcp >/dev/null || { echo "skip: libtiff-tools (tiffcp) missing"; exit 77; }
"$python" -c "import numpy" 2>/dev/null || { echo "skip: python3-numpy missing"; exit 77; }
convert="$VRI_BIN/vri-convert"

"$python" - <<'PY'
import struct, numpy as np
def page(name, pixels, sample_format):
    h, w = pixels.shape
    data = pixels.astype(pixels.dtype.newbyteorder("<")).tobytes()
    tags = [(256, 3, w), (257, 3, h), (258, 3, 16), (259, 3, 1), (262, 3, 1), (273, 4, 8),
            (277, 3, 1), (278, 3, h), (279, 4, len(data)), (339, 3, sample_format)]
    ifd = struct.pack("<H", len(tags)) + b"".join(struct.pack("<HHII", t, k, 1, v) for t, k, v in tags) + b"\0" * 4
    with open(name, "wb") as f:
        f.write(b"II*\0" + struct.pack("<I", 8 + len(data)) + data + ifd)
z, y, x = np.mgrid[0:3, 0:4, 0:5]
u = (1000 * z + 10 * y + x).astype(np.uint16)
for k in range(3):
    page("u%d.tif" % k, u[k], 1)
    page("s%d.tif" % k, (u[k].astype(np.int32) - 1500).astype(np.int16), 2)
page("wide.tif", np.zeros((4, 6), np.uint16), 1)
u.astype("<u2").tofile("expected_5x4x3_uint16.raw")
(u.astype(np.int32) - 1500).astype("<f4").tofile("expected_5x4x3_float32.raw")
PY
tiffcp u0.tif u1.tif u2.tif ustack.tif
tiffcp s0.tif s1.tif s2.tif sstack.tiff

"$convert" -q ustack.tif u.raw
cmp expected_5x4x3_uint16.raw u.raw
check_info() {  # FILE TYPE LO HI: dims 5x4x3, unit spacing, corner 0, the voxel type and normalisation range
  "$convert" --info --json "$1" | "$python" -c '
import json, sys
info, want = json.load(sys.stdin), sys.argv[1:]
assert info["dims"] == [5, 4, 3], info["dims"]
assert info["voxel_type"] == want[0], info["voxel_type"]
assert info["spacing"] == [1, 1, 1] and info["origin"] == [0, 0, 0], info
assert info["normalisation_range"] == [float(want[1]), float(want[2])], info["normalisation_range"]
' "$2" "$3" "$4" || fail "$1: --info is not as expected"
}
check_info ustack.tif uint16 0 65535

"$convert" -q sstack.tiff s.raw
cmp expected_5x4x3_float32.raw s.raw
check_info sstack.tiff float32 -32768 32767

# Pages of different sizes are refused, naming the page.
tiffcp u0.tif wide.tif mixed.tif
if "$convert" --info mixed.tif 2>err.txt; then fail "pages of different sizes were read"; fi
grep -q "^vri-convert: error: mixed.tif: page 1 is 6x4 uint16 with 1 channels, expected 5x4 uint16 with one, as page 0$" err.txt ||
  fail "mixed pages: $(cat err.txt)"
if "$convert" --info rgb_is_not_here.tif 2>err.txt; then fail "a missing TIFF was read"; fi
grep -q "rgb_is_not_here.tif: no such file" err.txt || fail "missing TIFF: $(cat err.txt)"
echo "formats_tiff: ok"
