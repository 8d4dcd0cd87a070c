#!/usr/bin/env bash
# vri's .vdb files as other programs read them, and theirs as vri reads them: OpenVDB's own Python
# binding (Debian python3-openvdb, which knows FloatGrid but not vri's former Int32Grid) opens vri's
# uint8, uint16 and float32 files and finds a fog volume of the raw values, vri's metadata and each voxel's
# centre where vri renders it; a grid written by that binding (half floats on disk, its own transform)
# comes back in vri with the same values and positions. vdb_print (libopenvdb-tools) lists the grid.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
python=/usr/bin/python3
"$python" -c "import pyopenvdb, numpy" 2>/dev/null || { echo "skip: python3-openvdb or python3-numpy missing"; exit 77; }
convert="$VRI_BIN/vri-convert"

# 5x4x3 volumes whose voxel (x,y,z) holds x + 5y + 20z (+ an offset), spacing 0.5 0.25 2, box corner (-1,2,10).
"$python" - <<'PY'
import numpy as np
v = np.fromfunction(lambda z, y, x: x + 5 * y + 20 * z, (3, 4, 5))
v.astype(np.uint8).tofile("a_5x4x3_uint8.raw")
(v * 1000 + 3).astype("<u2").tofile("b_5x4x3_uint16.raw")
(v * 0.5 - 7.25).astype("<f4").tofile("c_5x4x3_float32.raw")
PY
for f in a_5x4x3_uint8 b_5x4x3_uint16 c_5x4x3_float32; do
  "$convert" -q "$f.raw" "${f%%_*}.nhdr" --spacing 0.5,0.25,2
  # Move the box corner to (-1,2,10): NRRD's space origin is the first voxel's centre, a half voxel in.
  sed -i 's/^space origin: .*/space origin: (-0.75,2.125,11)/' "${f%%_*}.nhdr"
  "$convert" -q "${f%%_*}.nhdr" "$f.vdb"
done

"$python" - <<'PY'
import numpy as np, pyopenvdb as vdb
def check(name, dtype, scale, offset, type_name):
    grid = vdb.read(name + ".vdb", "density")
    assert grid.valueTypeName == "float", grid.valueTypeName
    assert grid.gridClass == vdb.GridClass.FOG_VOLUME, grid.gridClass
    assert grid.metadata["vri_voxel_type"] == type_name, grid.metadata
    assert tuple(grid.metadata["vri_dims"]) == (5, 4, 3), grid.metadata
    dense = np.zeros((5, 4, 3), np.float32)  # OpenVDB's arrays are indexed [x][y][z]
    grid.copyToArray(dense, (0, 0, 0))
    raw = np.fromfile(name + ".raw", dtype).reshape(3, 4, 5).transpose(2, 1, 0)
    assert (dense == raw.astype(np.float32)).all(), (dense, raw)
    x = grid.transform
    # Voxel (i,j,k)'s centre: corner (-1,2,10) + (index + 1/2) * spacing.
    for ijk in [(0, 0, 0), (4, 3, 2), (1, 2, 0)]:
        want = tuple(c + (i + 0.5) * s for c, i, s in zip((-1, 2, 10), ijk, (0.5, 0.25, 2)))
        assert tuple(x.indexToWorld(ijk)) == want, (ijk, x.indexToWorld(ijk), want)
    assert tuple(x.voxelSize()) == (0.5, 0.25, 2.0)
check("a_5x4x3_uint8", np.uint8, 1, 0, "uint8")
check("b_5x4x3_uint16", "<u2", 1, 0, "uint16")
check("c_5x4x3_float32", "<f4", 1, 0, "float32")

# A grid of OpenVDB's own making: half floats on disk, voxel size 0.5, voxel (0,0,0)'s centre at (3,4,5),
# active voxels from index (2,1,0) to (4,2,1).
grid = vdb.FloatGrid()
grid.name = "smoke"
grid.gridClass = vdb.GridClass.FOG_VOLUME
grid.saveFloatAsHalf = True
a = np.zeros((3, 2, 2), np.float32)
for i in range(3):
    for j in range(2):
        for k in range(2):
            a[i, j, k] = 1 + i + 0.25 * j + 0.5 * k  # exact in half
grid.copyFromArray(a, (2, 1, 0))
grid.transform = vdb.createLinearTransform(voxelSize=0.5)
grid.transform.translate((3, 4, 5))
other = vdb.FloatGrid()
other.name = "other"
vdb.write("foreign.vdb", grids=[other, grid])
PY

"$convert" -q --grid smoke foreign.vdb foreign.nhdr
json=$("$convert" --info --json --grid smoke foreign.vdb)
"$python" - "$json" <<'PY'
import json, sys, numpy as np
info = json.loads(sys.argv[1])
assert info["dims"] == [3, 2, 2], info["dims"]
assert info["voxel_type"] == "float32"
assert info["spacing"] == [0.5, 0.5, 0.5]
# Index (2,1,0)'s centre is (3,4,5) + (2,1,0) * 0.5 = (4,4.5,5); the box starts half a voxel below.
assert info["origin"] == [3.75, 4.25, 4.75], info["origin"]
v = np.fromfile("foreign.raw", "<f4").reshape(2, 2, 3)  # [z][y][x]
for i in range(3):
    for j in range(2):
        for k in range(2):
            assert v[k, j, i] == 1 + i + 0.25 * j + 0.5 * k, (i, j, k, v[k, j, i])
PY
grep -q "^space origin: (4,4.5,5)$" foreign.nhdr || fail "foreign.nhdr: $(cat foreign.nhdr)"

# Back to raw, byte for byte, from the FloatGrid of every voxel type.
for f in a_5x4x3_uint8 b_5x4x3_uint16 c_5x4x3_float32; do
  "$convert" -q "$f.vdb" "back_$f.raw"
  cmp "$f.raw" "back_$f.raw"
done

if command -v vdb_print >/dev/null; then
  listing=$(vdb_print -l a_5x4x3_uint8.vdb)
  grep -q "density" <<<"$listing" || fail "vdb_print does not list the grid: $listing"
  grep -qi "fog" <<<"$listing" || fail "vdb_print does not see a fog volume: $listing"
fi
echo "formats_vdb: ok"
