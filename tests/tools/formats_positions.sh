#!/usr/bin/env bash
# One volume in every format vri reads, written by vri and by independent tools, renders to the same image
# bit for bit with a camera fixed in world space: each format's voxels sit where vri renders them. NRRD,
# MetaImage and .vdb state the first voxel's centre; Inviwo .dat the box corner (its basis spans the box).
#   - vri's writers: .nhdr, .nrrd (attached), .dat, .vdb
#   - teem's unu (Debian teem-apps): a detached .nhdr and an attached gzip .nrrd, "centerings: cell"
#   - Python's zlib: a MetaImage .mha (LOCAL, compressed) and a detached .mhd
#   - a NRRD with "centers: node" along x renders as the cell file moved by half a voxel along x
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
python=/usr/bin/python3
"$python" -c "import numpy" 2>/dev/null || { echo "skip: python3-numpy missing"; exit 77; }
bin="$VRI_BIN"

# 6x5x4 uint16, spacing 0.5 0.25 2, box corner (-1, 2, 10): voxel (0,0,0)'s centre is (-0.75, 2.125, 11).
"$python" - <<'PY'
import numpy as np, zlib
z, y, x = np.mgrid[0:4, 0:5, 0:6]
v = (2000 * np.sin(x + 2 * y) + 3000 * z + 9000).astype("<u2")
v.tofile("vol_6x5x4_uint16.raw")
header = ("ObjectType = Image\nNDims = 3\nDimSize = 6 5 4\nElementType = MET_USHORT\n"
          "ElementSpacing = 0.5 0.25 2\nOffset = -0.75 2.125 11\nTransformMatrix = 1 0 0 0 1 0 0 0 1\n"
          "BinaryData = True\nBinaryDataByteOrderMSB = False\n")
packed = zlib.compress(v.tobytes())
with open("py.mha", "wb") as f:
    f.write((header + "CompressedData = True\nCompressedDataSize = %d\nElementDataFile = LOCAL\n" % len(packed)).encode())
    f.write(packed)
with open("py.mhd", "w") as f:
    f.write(header + "ElementDataFile = vol_6x5x4_uint16.raw\n")
PY
"$bin/vri-convert" -q vol_6x5x4_uint16.raw ref.nhdr --spacing 0.5,0.25,2
sed -i 's/^space origin: .*/space origin: (-0.75,2.125,11)/' ref.nhdr
for f in vri.nrrd vri.dat vri.vdb; do "$bin/vri-convert" -q ref.nhdr "$f"; done
grep -q "^Offset: -1 2 10$" vri.dat || fail "vri.dat: $(cat vri.dat)"

inputs=(vri.nrrd vri.dat vri.vdb py.mha py.mhd)
if command -v teem-unu >/dev/null || command -v unu >/dev/null; then
  unu=$(command -v teem-unu || command -v unu)
  "$unu" make -i vol_6x5x4_uint16.raw -t ushort -s 6 5 4 -e raw -en little -spc 3 -orig "(-0.75,2.125,11)" \
    -dirs "(0.5,0,0) (0,0.25,0) (0,0,2)" -cn cell cell cell -o unu.nhdr
  "$unu" save -i unu.nhdr -e gzip -f nrrd -o unu.nrrd
  grep -aq "^encoding: gzip" unu.nrrd || fail "unu did not write gzip"
  inputs+=(unu.nhdr unu.nrrd)
else
  echo "note: teem-apps (unu) missing, its files are not checked"
fi

cat > tf.yaml <<'YAML'
points:
  - [0.0, 0.0, 0.0, 0.0, 0.0]
  - [0.2, 0.9, 0.3, 0.1, 0.4]
  - [0.6, 0.2, 0.8, 0.4, 0.9]
  - [1.0, 0.1, 0.2, 0.9, 1.5]
YAML
render() { "$bin/vri-render" --volume "$1" --tf tf.yaml --size 40x32 --step 0.25 --eye 4,9,-6 --target 0.5,2.6,14 \
  --up 0,1,0 -o "$2" >/dev/null; }
same() { "$bin/vri-diff" "$1" "$2" --fail 0 --warn 0 >/dev/null || fail "$2 differs from $1"; }
render ref.nhdr ref.exr
for f in "${inputs[@]}"; do
  render "$f" "$f.exr"
  same ref.exr "$f.exr"
done

# The image shows the box: the same volume half a voxel further along x does not render the same.
sed 's/^space origin: (-0.75,/space origin: (-0.5,/' ref.nhdr > moved.nhdr
render moved.nhdr moved.exr
if "$bin/vri-diff" ref.exr moved.exr --fail 0 --warn 0 >/dev/null; then fail "moving the volume did not change the image"; fi
# The same first centre on a node x axis: the box starts on it, half a voxel further along x, as above.
sed 's/^centers: cell cell cell$/centers: node cell cell/' ref.nhdr > node.nhdr
grep -q "^centers: node cell cell$" node.nhdr || fail "node.nhdr: $(cat node.nhdr)"
render node.nhdr node.exr
same moved.exr node.exr
echo "formats_positions: ok"
