#!/usr/bin/env bash
# Bad input to the readers of issue 18: gzip NRRD, the converted voxel types, NRRD centerings, MetaImage
# .mhd/.mha, and .vdb values that do not fit the voxel type their metadata claim. Each case: the exit code,
# one stderr line naming the file (and line and field where a header is at fault), an unchanged work
# directory (lib/bad_input.sh).
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
source "$(dirname "${BASH_SOURCE[0]}")/lib/bad_input.sh"
python=/usr/bin/python3
"$python" -c "import numpy" 2>/dev/null || { echo "skip: python3-numpy missing"; exit 77; }
convert="$VRI_BIN/vri-convert"
E='^vri-convert: error: '

# --- inputs, made before the cases: the work directory must stay as it is from here on ---
"$python" - <<'PY'
import zlib, numpy as np
nhdr = "NRRD0004\ntype: %s\ndimension: 3\nsizes: 2 2 2\nendian: little\nencoding: %s\n%s"
def attached(name, type, encoding, data, extra=""):
    open(name, "wb").write((nhdr % (type, encoding, extra) + "\n").encode() + data)
eight = bytes(range(8))
attached("truncated.nrrd", "uchar", "gzip", zlib.compress(eight)[:5])
attached("short.nrrd", "uchar", "gzip", zlib.compress(eight[:7]))
attached("long.nrrd", "uchar", "gzip", zlib.compress(eight + b"x"))
attached("notgzip.nrrd", "uchar", "gzip", eight)
attached("skip.nrrd", "uchar", "gzip", zlib.compress(eight), "byte skip: 1\n")
attached("huge.nrrd", "double", "gzip", zlib.compress(eight), "")
open("huge.nrrd", "wb").write(b"NRRD0004\ntype: double\ndimension: 3\nsizes: 100000 100000 100000\nendian: little\n"
                              b"encoding: gzip\n\n" + zlib.compress(eight))
attached("int64.nrrd", "int64", "raw", bytes(64))
attached("centers.nrrd", "uchar", "raw", eight, "centers: cell node\n")
attached("centers-word.nrrd", "uchar", "raw", eight, "centers: cell middle cell\n")
attached("overflow.nrrd", "double", "raw", np.array([0, 0, 0, 0, 0, 1e300, 0, 0], "<f8").tobytes())
mha = "ObjectType = Image\nNDims = 3\nDimSize = 2 2 2\nElementType = %s\n%sElementDataFile = LOCAL\n"
def meta(name, type, data, extra=""):
    open(name, "wb").write((mha % (type, extra)).encode() + data)
meta("ok.mha", "MET_UCHAR", eight)
meta("type.mha", "MET_LONG_LONG", bytes(64))
meta("rotated.mha", "MET_UCHAR", eight, "TransformMatrix = 0 1 0 1 0 0 0 0 1\n")
meta("ascii.mha", "MET_UCHAR", eight, "BinaryData = False\n")
meta("channels.mha", "MET_UCHAR", eight * 3, "ElementNumberOfChannels = 3\n")
meta("badzlib.mha", "MET_UCHAR", eight, "CompressedData = True\n")
meta("spacing.mha", "MET_UCHAR", eight, "ElementSpacing = 1 0 1\n")
meta("dims.mha", "MET_UCHAR", eight, "")
open("dims.mha", "wb").write(b"NDims = 3\nDimSize = 2 2 1e30\nElementType = MET_UCHAR\nElementDataFile = LOCAL\n" + eight)
open("ndims.mha", "wb").write(b"NDims = 2\nDimSize = 2 2\nElementType = MET_UCHAR\nElementDataFile = LOCAL\n" + eight)
open("nodata.mhd", "wb").write(b"NDims = 3\nDimSize = 2 2 2\nElementType = MET_UCHAR\n")
open("noeq.mhd", "wb").write(b"NDims = 3\nDimSize 2 2 2\nElementDataFile = LOCAL\n")
open("missing.mhd", "wb").write(b"NDims = 3\nDimSize = 2 2 2\nElementType = MET_UCHAR\nElementDataFile = gone.raw\n")
open("shortdata.mhd", "wb").write(b"NDims = 3\nDimSize = 2 2 2\nElementType = MET_USHORT\nElementDataFile = d.raw\n")
open("d.raw", "wb").write(eight)
PY
# A vri .vdb of uint8 whose float grid holds 300 (python3-openvdb writes it, vri's metadata kept).
if "$python" -c "import pyopenvdb" 2>/dev/null; then
  printf '\x01\x02\x03\x04\x05\x06\x07\x08' > v_2x2x2_uint8.raw
  "$convert" -q v_2x2x2_uint8.raw v.vdb
  "$python" - <<'PY'
import pyopenvdb as vdb
grid = vdb.read("v.vdb", "density")
grid.getAccessor().setValueOn((1, 0, 0), 300.0)
vdb.write("over.vdb", grids=[grid])
grid.getAccessor().setValueOn((1, 0, 0), 2.5)
vdb.write("fraction.vdb", grids=[grid])
PY
fi

# --- cases ---
bad 1 "${E}truncated\.nrrd: gzip data of 2x2x2 uint8: the compressed data end after [0-9]+ bytes, expected 8$" -- "$convert" --info truncated.nrrd
bad 1 "${E}short\.nrrd: gzip data of 2x2x2 uint8: the compressed data hold 7 bytes, expected 8$" -- "$convert" --info short.nrrd
bad 1 "${E}long\.nrrd: gzip data of 2x2x2 uint8: the compressed data hold more than the expected 8 bytes$" -- "$convert" --info long.nrrd
bad 1 "${E}notgzip\.nrrd: gzip data of 2x2x2 uint8: not a valid gzip/zlib stream" -- "$convert" --info notgzip.nrrd
bad 1 "${E}skip\.nrrd:7: byte skip: skipping bytes of gzip-encoded data is not supported$" -- "$convert" --info skip.nrrd
bad 1 "${E}huge\.nrrd: 100000x100000x100000 float64: needs 8000000000000000 bytes, limit" -- "$convert" --info huge.nrrd
bad 1 "${E}int64\.nrrd:2: type: 'int64' is not supported" -- "$convert" --info int64.nrrd
bad 1 "${E}centers\.nrrd:7: centers: expected 3 centerings" -- "$convert" --info centers.nrrd
bad 1 "${E}centers-word\.nrrd:7: centers: expected cell, node, \?\?\? or none, got 'middle'$" -- "$convert" --info centers-word.nrrd
bad 1 "${E}overflow\.nrrd: float64 voxel 5 is 1e\+300, beyond float32's range" -- "$convert" --info overflow.nrrd
bad 1 "${E}type\.mha:4: ElementType: 'MET_LONG_LONG' is not supported" -- "$convert" --info type.mha
bad 1 "${E}rotated\.mha:5: TransformMatrix: only the identity is supported" -- "$convert" --info rotated.mha
bad 1 "${E}ascii\.mha:5: BinaryData: ASCII voxel data are not supported" -- "$convert" --info ascii.mha
bad 1 "${E}channels\.mha:5: ElementNumberOfChannels: must be 1" -- "$convert" --info channels.mha
bad 1 "${E}badzlib\.mha: gzip data of 2x2x2 uint8: not a valid gzip/zlib stream" -- "$convert" --info badzlib.mha
bad 1 "${E}spacing\.mha:5: ElementSpacing: expected positive spacings" -- "$convert" --info spacing.mha
bad 1 "${E}dims\.mha:2: DimSize: expected three positive integers" -- "$convert" --info dims.mha
bad 1 "${E}ndims\.mha:1: NDims: must be 3" -- "$convert" --info ndims.mha
bad 1 "${E}nodata\.mhd: no ElementDataFile line" -- "$convert" --info nodata.mhd
bad 1 "${E}noeq\.mhd:2: expected 'Key = Value', got 'DimSize 2 2 2'$" -- "$convert" --info noeq.mhd
bad 1 "${E}missing\.mhd: ElementDataFile gone\.raw: no such file$" -- "$convert" --info missing.mhd
bad 1 "${E}shortdata\.mhd: ElementDataFile d\.raw: file is 8 bytes, expected 16 for 2x2x2 uint16$" -- "$convert" --info shortdata.mhd
bad 1 "${E}ok\.mha: dims and voxel type are for raw files; a \.mha file describes its own layout$" -- "$convert" --info ok.mha --dims 2,2,2 --type uint8
if [ -e over.vdb ]; then
  bad 1 "${E}over\.vdb: grid 'density' \(float\) holds 300 at index \(1,0,0\), expected a whole number 0\.\.255 \(uint8\)$" -- "$convert" --info over.vdb
  bad 1 "${E}fraction\.vdb: grid 'density' \(float\) holds 2\.5 at index \(1,0,0\), expected a whole number" -- "$convert" --info fraction.vdb
fi
bad_done
