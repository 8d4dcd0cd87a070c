#!/usr/bin/env bash
# A volume as bricks (issue 49): vri-render --bricks --brick reads only a brick's stored box of a raw file (or
# of a NRRD, MetaImage, Inviwo .dat or TIFF stack holding its voxels as vri keeps them) and renders its layer; vri-merge-tiles --layer joins every brick's layer into the unbricked render's image
# within the bound its stats give, the same bits in any order and for tiles of the layers; a float volume's
# range is the whole file's; what a brick cannot do is refused naming the option.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
bin=${VRI_BIN:?}
source "$(dirname "${BASH_SOURCE[0]}")/lib/blob.sh" && write_blob_scene

# 24x20x16 voxels of noise, as uint8 and as float32 (values from -1 to 2: the range is the data's).
/usr/bin/python3 - <<'PY'
import random, struct
random.seed(3)
values = [random.randrange(256) for _ in range(24 * 20 * 16)]
open("noise_24x20x16_uint8.raw", "wb").write(bytes(values))
open("noise_24x20x16_float32.raw", "wb").write(b"".join(struct.pack("<f", v / 85.0 - 1.0) for v in values))
PY

# joined VOLUME NX,NY,NZ ARGS...: the unbricked render and every brick's layer, joined forwards and backwards;
# checks the join against the whole within its bound and the two joins bit for bit.
joined() {
  local volume=$1 grid=$2
  shift 2
  local scene=(--volume "$volume" --tf tf.yaml --size 37x29 --eye 60,-40,50 -q "$@")
  "$bin/vri-render" "${scene[@]}" -o whole.exr --stats whole.json
  local forward=() backward=() nx ny nz
  IFS=, read -r nx ny nz <<< "$grid"
  rm -f layer-*
  for ((z = 0; z < nz; ++z)); do for ((y = 0; y < ny; ++y)); do for ((x = 0; x < nx; ++x)); do
    "$bin/vri-render" "${scene[@]}" --bricks "$grid" --brick "$x,$y,$z" -o "layer-$x-$y-$z.exr" \
      --stats "layer-$x-$y-$z.json"
    forward+=(--layer "layer-$x-$y-$z.exr" "layer-$x-$y-$z.json")
    backward=(--layer "layer-$x-$y-$z.exr" "layer-$x-$y-$z.json" "${backward[@]}")
  done; done; done
  "$bin/vri-merge-tiles" "${forward[@]}" -o joined.exr --stats joined.json --png joined.png
  "$bin/vri-merge-tiles" "${backward[@]}" -o backward.exr
  /usr/bin/python3 - "$volume" "$grid" <<'PY' || fail "$volume as $grid bricks $*"
import json, sys
import numpy as np
import OpenImageIO as oiio
def pixels(path):
    return oiio.ImageBuf(path).get_pixels(oiio.FLOAT)
whole, joined, backward = pixels("whole.exr"), pixels("joined.exr"), pixels("backward.exr")
assert joined.shape == whole.shape, (joined.shape, whole.shape)
assert np.array_equal(joined.view(np.uint32), backward.view(np.uint32)), "the order of the layers moved a bit"
record = json.load(open("joined.json"))
bound = record["join"]["bound_max"]
worst = float(np.abs(joined.astype(np.float64) - whole).max())
assert 0 < bound < 1e-5, bound
assert worst <= bound, (worst, bound)
assert record["scene"]["storage"] == "bricks" and len(record["layers"]) == eval(sys.argv[2].replace(",", "*"))
layer, unbricked = json.load(open("layer-0-0-0.json")), json.load(open("whole.json"))
lo, hi = layer["scene"]["brick"]["stored_lo"], layer["scene"]["brick"]["stored_hi"]
size = 4 if "float32" in sys.argv[1] or "int16" in sys.argv[1] else 1  # int16 is kept as float32
assert layer["scene"]["volume_bytes"] == (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]) * size
if sys.argv[2] != "1,1,1":
    assert layer["scene"]["volume_bytes"] < unbricked["scene"]["volume_bytes"], "a brick kept the whole volume"
assert layer["scene"]["normalisation_range"] == unbricked["scene"]["normalisation_range"], "the range is the whole's"
PY
}

joined noise_24x20x16_uint8.raw 3,2,2 --method riemann --step 0.5
cp joined.exr raw-joined.exr
joined noise_24x20x16_uint8.raw 1,1,1 --method composite --step 0.7 --convention node
joined noise_24x20x16_uint8.raw 2,3,1 --method riemann --step 0.3 --jitter --seed 5
joined noise_24x20x16_float32.raw 2,2,2 --method composite --step 0.5
joined blob_8x8x8_uint8.raw 2,2,2 --method riemann --step 0.25

# NRRD whose voxels vri keeps as stored, detached (.nhdr) and attached (.nrrd) as vri-convert writes them: a
# brick is read by offset as a raw file's is, its layer bit for bit the raw file's brick's. Only the brick's
# box is read: a NaN outside it stops the whole render, not the brick's (its range given, so that nothing
# else of the file is read for it).
"$bin/vri-convert" noise_24x20x16_uint8.raw noise-uint8.nhdr 2> /dev/null
"$bin/vri-convert" noise_24x20x16_float32.raw noise-float32.nrrd 2> /dev/null
joined noise-uint8.nhdr 3,2,2 --method riemann --step 0.5
joined noise-float32.nrrd 2,2,2 --method composite --step 0.5
scene=(--tf tf.yaml --size 37x29 --eye 60,-40,50 -q --method riemann --step 0.5 --bricks 3,2,2 --brick 1,1,0)
"$bin/vri-render" --volume noise_24x20x16_uint8.raw "${scene[@]}" -o raw-layer.exr
"$bin/vri-render" --volume noise-uint8.nhdr "${scene[@]}" -o nhdr-layer.exr --stats nhdr-layer.json
"$bin/vri-diff" raw-layer.exr nhdr-layer.exr --fail 0 > /dev/null || fail "a NRRD's brick differs from the raw file's"
# Its record names both files the image comes from, the header and the data file it names, with their digests.
/usr/bin/python3 - "$(sha512sum < noise-uint8.nhdr | cut -d' ' -f1)" "$(sha512sum < noise-uint8.raw | cut -d' ' -f1)" <<'PY' ||
import json, os, sys
inputs = {os.path.basename(i["path"]): i["sha512"] for i in json.load(open("nhdr-layer.json"))["inputs"]}
assert inputs == {"noise-uint8.nhdr": sys.argv[1], "noise-uint8.raw": sys.argv[2], "tf.yaml": inputs.get("tf.yaml")}, inputs
PY
  fail "the NRRD's stats do not name its data file: $(cat nhdr-layer.json)"
# An Inviwo .dat's raw file is read by offset too: its brick bit for bit the raw file's, and only its box read
# (a NaN in the last voxel, DataRange given, stops the whole render and not brick 0,0,0).
"$bin/vri-convert" noise_24x20x16_uint8.raw noise-uint8.dat 2> /dev/null
joined noise-uint8.dat 2,2,1 --method riemann --step 0.5
"$bin/vri-render" --volume noise-uint8.dat "${scene[@]}" -o dat-layer.exr
"$bin/vri-diff" raw-layer.exr dat-layer.exr --fail 0 > /dev/null || fail "a .dat's brick differs from the raw file's"
/usr/bin/python3 - <<'PY'
import random, struct
random.seed(4)
values = [random.randrange(256) / 85.0 - 1.0 for _ in range(24 * 20 * 16)]
values[-1] = float("nan")
open("nan-dat.raw", "wb").write(b"".join(struct.pack("<f", v) for v in values))
open("nan.dat", "w").write("Rawfile: nan-dat.raw\nResolution: 24 20 16\nFormat: FLOAT32\nDataRange: -1 2\n")
PY
dat=(--volume nan.dat --tf tf.yaml --size 37x29 --eye 60,-40,50 -q)
"$bin/vri-render" "${dat[@]}" --bricks 2,2,2 --brick 0,0,0 -o nan-dat-layer.exr || fail "a .dat brick read a voxel outside its box"
if "$bin/vri-render" "${dat[@]}" -o nan-dat-whole.exr 2> nan-dat.txt; then fail "the whole .dat render read no NaN"; fi
grep -q "nan.dat: voxel 7679 (x 23, y 19, z 15) is nan" nan-dat.txt || fail "the .dat's NaN: $(cat nan-dat.txt)"
# MetaImage likewise, its ElementDataFile or its LOCAL data after the header: a brick bit for bit the raw
# file's, and a NaN in an .mha's last voxel stops the whole render and not brick 0,0,0 (--range given).
/usr/bin/python3 - <<'PY'
import random, struct
open("noise.mhd", "w").write("ObjectType = Image\nNDims = 3\nDimSize = 24 20 16\nElementType = MET_UCHAR\n"
                             "ElementDataFile = noise_24x20x16_uint8.raw\n")
random.seed(6)
values = [random.randrange(256) / 85.0 - 1.0 for _ in range(24 * 20 * 16)]
values[-1] = float("nan")
open("nan.mha", "wb").write(b"ObjectType = Image\nNDims = 3\nDimSize = 24 20 16\nElementType = MET_FLOAT\n"
                            b"ElementDataFile = LOCAL\n" + b"".join(struct.pack("<f", v) for v in values))
PY
"$bin/vri-render" --volume noise.mhd "${scene[@]}" -o mhd-layer.exr
"$bin/vri-diff" raw-layer.exr mhd-layer.exr --fail 0 > /dev/null || fail "a MetaImage's brick differs from the raw file's"
mha=(--volume nan.mha --tf tf.yaml --size 37x29 --eye 60,-40,50 -q --range -1,2)
"$bin/vri-render" "${mha[@]}" --bricks 2,2,2 --brick 0,0,0 -o nan-mha-layer.exr || fail "an .mha brick read a voxel outside its box"
if "$bin/vri-render" "${mha[@]}" -o nan-mha-whole.exr 2> nan-mha.txt; then fail "the whole .mha render read no NaN"; fi
grep -q "nan.mha: voxel 7679 (x 23, y 19, z 15) is nan" nan-mha.txt || fail "the .mha's NaN: $(cat nan-mha.txt)"
# TIFF stacks (a page a z slice) whose voxels vri keeps as stored (uint8, uint16, float32) are read by their
# pages' rows: a uint8 stack's brick bit for bit the raw file's, in strips of 3 rows, deflated; a float32
# stack's range scanned a page at a time; a NaN in its last voxel stops the whole render and the range's scan,
# named alike, and not brick 0,0,0 (--range given). An int16 stack (vri converts it) is read whole and cut.
/usr/bin/python3 - <<'PY'
import random
import numpy as np
import OpenImageIO as oiio
def stack(name, voxels, compression="none"):  # voxels[z][y][x]
    specs = []
    for page in voxels:
        spec = oiio.ImageSpec(page.shape[1], page.shape[0], 1, oiio.TypeDesc({"float32": "float"}.get(page.dtype.name, page.dtype.name)))
        spec.attribute("compression", compression)
        spec.attribute("tiff:RowsPerStrip", 3)
        specs.append(spec)
    out = oiio.ImageOutput.create(name)
    assert out.open(name, specs), oiio.geterror()
    for z, page in enumerate(voxels):
        assert z == 0 or out.open(name, specs[z], "AppendSubimage"), out.geterror()
        assert out.write_image(np.ascontiguousarray(page[:, :, None])), out.geterror()
    out.close()
u8 = np.fromfile("noise_24x20x16_uint8.raw", np.uint8).reshape(16, 20, 24)
stack("noise-uint8.tif", u8, "zip")
stack("noise-float32.tif", np.fromfile("noise_24x20x16_float32.raw", "<f4").reshape(16, 20, 24))
stack("noise-int16.tif", (u8.astype(np.int16) - 100).astype(np.int16))
random.seed(7)
nan = np.array([random.randrange(256) / 85.0 - 1.0 for _ in range(24 * 20 * 16)], np.float32).reshape(16, 20, 24)
nan[-1, -1, -1] = np.nan
stack("nan.tif", nan)
PY
joined noise-uint8.tif 3,2,2 --method riemann --step 0.5
"$bin/vri-diff" raw-joined.exr joined.exr --fail 0 > /dev/null || fail "a TIFF stack's bricks joined differ from the raw file's"
joined noise-float32.tif 2,2,2 --method composite --step 0.5
joined noise-int16.tif 2,1,2 --method riemann --step 0.5
scene=(--tf tf.yaml --size 37x29 --eye 60,-40,50 -q --method riemann --step 0.5 --bricks 3,2,2 --brick 1,1,0)
"$bin/vri-render" --volume noise-uint8.tif "${scene[@]}" -o tif-layer.exr
"$bin/vri-diff" raw-layer.exr tif-layer.exr --fail 0 > /dev/null || fail "a TIFF stack's brick differs from the raw file's"
tif=(--volume nan.tif --tf tf.yaml --size 37x29 --eye 60,-40,50 -q)
"$bin/vri-render" "${tif[@]}" --range -1,2 --bricks 2,2,2 --brick 0,0,0 -o nan-tif-layer.exr ||
  fail "a TIFF brick read a voxel outside its box"
if "$bin/vri-render" "${tif[@]}" -o nan-tif-whole.exr 2> nan-tif.txt; then fail "the whole TIFF render read no NaN"; fi
if "$bin/vri-render" "${tif[@]}" --bricks 2,2,2 --brick 0,0,0 -o nan-tif-range.exr 2> nan-tif-range.txt; then
  fail "the TIFF brick's range read no NaN"
fi
for txt in nan-tif.txt nan-tif-range.txt; do
  grep -qx "vri-render: error: nan.tif: voxel 7679 (x 23, y 19, z 15) is nan: float volumes must hold finite values" "$txt" ||
    fail "the TIFF's NaN ($txt): $(cat "$txt")"
done
/usr/bin/python3 - <<'PY'
import random, struct
random.seed(3)
values = [random.randrange(256) / 85.0 - 1.0 for _ in range(24 * 20 * 16)]
values[-1] = float("nan")
header = b"NRRD0004\ntype: float\ndimension: 3\nsizes: 24 20 16\nendian: little\nencoding: raw\n\n"
open("nan.nrrd", "wb").write(header + b"".join(struct.pack("<f", v) for v in values))
PY
# Everything the header says, read by offset, is what the whole read says: a detached uint16 big-endian NRRD
# with an origin, spacings, vri_range and its data as the last bytes of a file that begins with other bytes;
# its brick bit for bit that of a gzip-encoded copy, which is read whole and cut.
/usr/bin/python3 - <<'PY'
import gzip, random, struct
random.seed(5)
data = b"".join(struct.pack(">H", random.randrange(4000)) for _ in range(24 * 20 * 16))
head = ("NRRD0004\ntype: uint16\ndimension: 3\nsizes: 24 20 16\nendian: big\nspacings: 0.5 0.75 1.25\n"
        "space origin: (3,-2,7)\n")
open("u16.data", "wb").write(b"something before the voxels" + data)
open("u16.nhdr", "w").write(head + "encoding: raw\nbyte skip: -1\ndata file: u16.data\nvri_range:=100 3900\n\n")
open("u16gz.nrrd", "wb").write((head + "encoding: gzip\nvri_range:=100 3900\n\n").encode() + gzip.compress(data))
PY
scene=(--tf tf.yaml --size 37x29 --eye 60,-40,50 -q --method riemann --step 0.3 --bricks 2,2,2 --brick 1,0,1)
"$bin/vri-render" --volume u16.nhdr "${scene[@]}" -o u16-layer.exr --stats u16-layer.json
"$bin/vri-render" --volume u16gz.nrrd "${scene[@]}" -o u16gz-layer.exr --stats u16gz-layer.json
"$bin/vri-diff" u16-layer.exr u16gz-layer.exr --fail 0 > /dev/null || fail "a NRRD brick read by offset differs from the one cut from the whole"
/usr/bin/python3 - <<'PY' || fail "the NRRD brick's scene differs from the whole read's"
import json
a, b = (json.load(open(f))["scene"] for f in ("u16-layer.json", "u16gz-layer.json"))
for key in ("normalisation_range", "volume_bytes", "brick"):
    assert a[key] == b[key], (key, a[key], b[key])
assert a["normalisation_range"] == [100.0, 3900.0], a["normalisation_range"]
PY
scene=(--volume nan.nrrd --tf tf.yaml --size 37x29 --eye 60,-40,50 -q --range -1,2)
"$bin/vri-render" "${scene[@]}" --bricks 2,2,2 --brick 0,0,0 -o nan-layer.exr || fail "a brick read a voxel outside its box"
if "$bin/vri-render" "${scene[@]}" -o nan-whole.exr 2> nan.txt; then fail "the whole render read no NaN"; fi
grep -q "nan.nrrd: voxel 7679 (x 23, y 19, z 15) is nan" nan.txt || { cat nan.txt; fail "the NaN was not named"; }
# A brick refuses what its whole volume refuses, in the same words: a NaN named by its place in the volume, a
# box beyond double's range by the volume's extent (13 voxels of 1e307 fit in a double, the volume's 24 do
# not), a box over the byte limit by its file (and by the header that names it).
if "$bin/vri-render" "${scene[@]}" --bricks 2,2,2 --brick 1,1,1 -o nan-brick.exr 2> nan-brick.txt; then fail "the brick read no NaN"; fi
grep -q "nan.nrrd: voxel 7679 (x 23, y 19, z 15) is nan" nan-brick.txt || fail "the brick's NaN: $(cat nan-brick.txt)"
# Without a range a float brick's normalisation streams the whole file, and the NaN it meets there is named as
# the whole read names it, by the volume and its place in it.
if "$bin/vri-render" --volume nan.nrrd --tf tf.yaml --size 37x29 --eye 60,-40,50 -q --bricks 2,2,2 --brick 0,0,0 \
  -o nan-range.exr 2> nan-range.txt; then fail "the brick's range read no NaN"; fi
grep -qx "vri-render: error: nan.nrrd: voxel 7679 (x 23, y 19, z 15) is nan: float volumes must hold finite values" nan-range.txt ||
  fail "the range's NaN: $(cat nan-range.txt)"
far=(--volume noise_24x20x16_uint8.raw --tf tf.yaml --size 37x29 --eye 60,-40,50 -q --spacing 1e307,1,1)
for brick in "" "--bricks 2,1,1 --brick 0,0,0"; do
  if "$bin/vri-render" "${far[@]}" $brick -o far.exr 2> far.txt; then fail "a box beyond double's range rendered ($brick)"; fi
  grep -qx "vri-render: error: --spacing 1e307,1,1: the box (origin 0 + 24 voxels x spacing 1e+307 along x) is beyond the range of a double" far.txt ||
    fail "($brick) $(cat far.txt)"
done
for volume in noise_24x20x16_uint8.raw noise-uint8.nhdr; do
  if VRI_MAX_BYTES=500 "$bin/vri-render" --volume "$volume" --tf tf.yaml --size 37x29 --eye 60,-40,50 -q --bricks 3,2,2 --brick 1,1,0 \
    -o big.exr 2> "$volume.txt"; then fail "$volume: a brick over the byte limit rendered"; fi
done
grep -qx "vri-render: error: noise_24x20x16_uint8.raw: a 9x10x9 uint8 volume: needs 810 bytes, limit 500 (VRI_MAX_BYTES)" \
  noise_24x20x16_uint8.raw.txt || fail "$(cat noise_24x20x16_uint8.raw.txt)"
grep -qx "vri-render: error: noise-uint8.nhdr: data file noise-uint8.raw: a 9x10x9 uint8 volume: needs 810 bytes, limit 500 (VRI_MAX_BYTES)" \
  noise-uint8.nhdr.txt || fail "$(cat noise-uint8.nhdr.txt)"

# A brick takes its volume's digest from the record its launcher made (VRI_INPUT_DIGESTS, as vri-run sets it:
# util/input_digest.h) instead of reading the whole file, and says so; a record the file no longer fits (written
# since: another modification time) is not used.
/usr/bin/python3 - <<'PY'
import json, os
st = os.stat("noise_24x20x16_uint8.raw")
json.dump({"files": [{"path": os.path.abspath("noise_24x20x16_uint8.raw"), "size": st.st_size,
                      "mtime_ns": st.st_mtime_ns, "sha512": "from-the-record"}]}, open("record.json", "w"))
PY
brick=(--volume noise_24x20x16_uint8.raw --tf tf.yaml --size 37x29 --eye 60,-40,50 -q --bricks 2,2,1 --brick 0,1,0)
VRI_INPUT_DIGESTS=$PWD/record.json "$bin/vri-render" "${brick[@]}" -o recorded.exr --stats recorded.json
touch -d "@$(($(date +%s) + 5))" noise_24x20x16_uint8.raw
VRI_INPUT_DIGESTS=$PWD/record.json "$bin/vri-render" "${brick[@]}" -o computed.exr --stats computed.json
/usr/bin/python3 - "$PWD/record.json" "$(sha512sum < noise_24x20x16_uint8.raw | cut -d' ' -f1)" <<'PY' || fail "the digests' record"
import json, sys
recorded, computed = (json.load(open(f)) for f in ("recorded.json", "computed.json"))
assert recorded["inputs"][0]["sha512"] == "from-the-record", recorded["inputs"]
assert recorded["input_digests_from"] == sys.argv[1], recorded.get("input_digests_from")
assert computed["inputs"][0]["sha512"] == sys.argv[2], computed["inputs"]
assert "input_digests_from" not in computed, computed["input_digests_from"]
PY

# A brick's layer in tiles: the tiles merged give the layer, bit for bit.
scene=(--volume noise_24x20x16_uint8.raw --tf tf.yaml --size 37x29 --eye 60,-40,50 -q --bricks 2,2,1 --brick 1,0,0)
"$bin/vri-render" "${scene[@]}" -o layer.exr --stats layer.json
"$bin/vri-render" "${scene[@]}" --region 0,0,37,12 -o top.exr --stats top.json
"$bin/vri-render" "${scene[@]}" --region 0,12,37,17 -o bottom.exr --stats bottom.json
/usr/bin/python3 - <<'PY' || fail "a layer's tiles are not the layer"
import numpy as np
import OpenImageIO as oiio
layer = oiio.ImageBuf("layer.exr").get_pixels(oiio.FLOAT)
tiles = np.concatenate([oiio.ImageBuf(f).get_pixels(oiio.FLOAT) for f in ("top.exr", "bottom.exr")])
assert layer.shape[2] == 5 and np.array_equal(layer.view(np.uint32), tiles.view(np.uint32))
PY
# vri-merge-tiles --tile joins a layer's tiles into the layer, bit for bit, which then joins with the other
# bricks' layers as the untiled one does: tiles and bricks combined.
"$bin/vri-merge-tiles" --tile top.exr top.json --tile bottom.exr bottom.json -o merged-layer.exr --stats merged-layer.json
"$bin/vri-diff" layer.exr merged-layer.exr --fail 0 > /dev/null || fail "the merged tiles are not the layer"
/usr/bin/python3 - <<'PY' || fail "the merged layer's channels"
import OpenImageIO as oiio
spec = oiio.ImageBuf("merged-layer.exr").spec()
assert list(spec.channelnames) == ["R", "G", "B", "A", "brick_order"], spec.channelnames
a, b = (oiio.ImageBuf(f).get_pixels(oiio.FLOAT) for f in ("layer.exr", "merged-layer.exr"))
assert (a.view("uint32") == b.view("uint32")).all()
PY
layers=()
for b in 0,0,0 0,1,0 1,1,0; do
  "$bin/vri-render" "${scene[@]/1,0,0/$b}" -o "tiled-layer-$b.exr" --stats "tiled-layer-$b.json"
  layers+=(--layer "tiled-layer-$b.exr" "tiled-layer-$b.json")
done
"$bin/vri-merge-tiles" "${layers[@]}" --layer layer.exr layer.json -o joined-untiled.exr
"$bin/vri-merge-tiles" "${layers[@]}" --layer merged-layer.exr merged-layer.json -o joined-tiled.exr
"$bin/vri-diff" joined-untiled.exr joined-tiled.exr --fail 0 > /dev/null || fail "a layer merged from tiles joins otherwise"

# An experiment's run in bricks and tiles (vri-run): each brick's layer joined from its tiles, then the
# bricks joined: bit for bit the run in bricks alone.
cat > both.yaml <<'YAML'
name: both
title: bricks and tiles
paper: {paper: none, item: bricks, says: a test}
scenes:
  noise: {volume: noise_24x20x16_uint8.raw, convention: cell, tf: tf.yaml, size: [37, 29],
          camera: {eye: [60, -40, 50], target: [12, 10, 8], up: [0, 0, 1]}}
methods:
  bricked: {method: riemann, step: 0.5, bricks: [2, 1, 2]}
  tiled: {method: riemann, step: 0.5, bricks: [2, 1, 2], tiles: 3}
YAML
"$bin/vri-run" --results runs both.yaml 2> both.txt || { cat both.txt; fail "the run in bricks and tiles failed"; }
[ -f runs/both/tiled.brick-1-0-1.tile-3.exr ] || fail "no tile of a brick: $(ls runs/both)"
"$bin/vri-diff" runs/both/bricked.exr runs/both/tiled.exr --fail 0 > /dev/null || fail "bricks in tiles join otherwise"

# A header volume's data file keys vri-run's cache with the header: a run again is cached, and a changed
# .raw (the header untouched) renders again.
mkdir -p hdr && cp noise-uint8.nhdr noise-uint8.raw hdr/
cat > hdr/header.yaml <<'YAML'
name: header
title: a header's data file in the cache
paper: {paper: none, item: cache, says: a test}
scenes:
  noise: {volume: noise-uint8.nhdr, convention: cell, tf: ../tf.yaml, size: [37, 29],
          camera: {eye: [60, -40, 50], target: [12, 10, 8], up: [0, 0, 1]}}
methods:
  riemann: {step: 0.5}
YAML
"$bin/vri-run" --results hdr/runs hdr/header.yaml 2> hdr/first.txt || { cat hdr/first.txt; fail "the header run failed"; }
"$bin/vri-run" --results hdr/runs hdr/header.yaml 2> hdr/again.txt || { cat hdr/again.txt; fail "the header run again failed"; }
grep -q "1 steps, 0 ran, 1 cached" hdr/again.txt || fail "the run again was not cached: $(cat hdr/again.txt)"
/usr/bin/python3 - <<'PY'
data = bytearray(open("hdr/noise-uint8.raw", "rb").read())
data[100] ^= 0xFF
open("hdr/noise-uint8.raw", "wb").write(bytes(data))
PY
"$bin/vri-run" --results hdr/runs hdr/header.yaml 2> hdr/changed.txt || { cat hdr/changed.txt; fail "the run after the change failed"; }
grep -q "1 steps, 1 ran, 0 cached" hdr/changed.txt || fail "a changed data file did not render again: $(cat hdr/changed.txt)"

# Refusals: one line naming the option, exit 1 (64 for usage).
expect() {
  local code=$1 pattern=$2
  shift 2
  set +e
  "$@" > out.txt 2> err.txt
  local rc=$?
  set -e
  [ "$rc" -eq "$code" ] || fail "$* exited $rc, expected $code: $(cat err.txt)"
  grep -Eq "$pattern" err.txt || fail "$* said: $(cat err.txt) (expected $pattern)"
  [ "$(wc -l < err.txt)" -eq 1 ] || fail "$* said more than one line: $(cat err.txt)"
}
base=(--volume noise_24x20x16_uint8.raw --tf tf.yaml --size 8x6 -q -o x.exr)
expect 64 "brick" "$bin/vri-render" "${base[@]}" --bricks 2,2,2
expect 1 "^vri-render: error: --brick: brick 2,0,0 is not in the 2,2,2 grid" "$bin/vri-render" "${base[@]}" --bricks 2,2,2 --brick 2,0,0
expect 1 "^vri-render: error: --bricks: expected 1 to 16 bricks along z" "$bin/vri-render" "${base[@]}" --bricks 2,2,17 --brick 0,0,0
expect 1 "^vri-render: error: --brick: renders riemann and composite" "$bin/vri-render" "${base[@]}" --bricks 2,2,2 --brick 0,0,0 --method coupled
expect 1 "^vri-render: error: --brick: renders in double" "$bin/vri-render" "${base[@]}" --bricks 2,2,2 --brick 0,0,0 --precision float
expect 1 "^vri-render: error: --method exact: not for a brick yet" "$bin/vri-render" "${base[@]}" --bricks 2,2,2 --brick 0,0,0 --method exact
expect 1 "^vri-render: error: --bricks: cuts dense volumes" "$bin/vri-render" "${base[@]}" --bricks 2,2,2 --brick 0,0,0 --storage sparse
expect 1 "^vri-render: error: --clamp: clamps the joined image" "$bin/vri-render" "${base[@]}" --bricks 2,2,2 --brick 0,0,0 --clamp
joined blob_8x8x8_uint8.raw 2,1,1 --method riemann
expect 1 "^vri-merge-tiles: error: --layer: no layer of brick 1,0,0 of the 2,1,1 grid" \
  "$bin/vri-merge-tiles" --layer layer-0-0-0.exr layer-0-0-0.json -o y.exr
expect 1 "^vri-merge-tiles: error: .*layer-1-0-0.json: brick 1,0,0 is given twice" \
  "$bin/vri-merge-tiles" --layer layer-0-0-0.exr layer-0-0-0.json --layer layer-1-0-0.exr layer-1-0-0.json \
  --layer layer-1-0-0.exr layer-1-0-0.json -o y.exr
expect 1 "^vri-merge-tiles: error: whole.json: not a brick's stats" \
  "$bin/vri-merge-tiles" --layer whole.exr whole.json -o y.exr
[ ! -e y.exr ] || fail "a refused join wrote its output"
# An experiment's `bricks:`: a step per brick, the join writing the run's files, compared as any run.
cat > bricked.yaml <<'YAML'
name: bricked
title: A volume as bricks
paper: {paper: A, item: none, says: a test}
scenes:
  noise: {volume: noise_24x20x16_uint8.raw, convention: cell, tf: tf.yaml, size: [37, 29],
          camera: {eye: [60, -40, 50], target: [12, 10, 8], up: [0, 0, 1]}}
methods:
  whole: {method: riemann, step: 0.5}
  bricked: {method: riemann, step: 0.5, bricks: [2, 1, 2]}
comparisons:
  vs-whole: {reference: whole, thresholds: [1e-5]}
YAML
"$bin/vri-run" --jobs 2 --results runs bricked.yaml 2> run.txt || fail "vri-run with bricks: $(cat run.txt)"
grep -q "vri-run: bricked: 7 steps, 7 ran" run.txt || fail "the bricked experiment's steps: $(cat run.txt)"
/usr/bin/python3 - <<'PY' || fail "the bricked run against the whole"
import glob, json
[path] = glob.glob("runs/bricked/vs-whole-*.json")
diff = json.load(open(path))
worst = max(c["max_abs"] for c in diff["channels"])
bound = json.load(open("runs/bricked/bricked.json"))["join"]["bound_max"]
assert worst <= bound, (worst, bound)
PY
sed 's/bricks: \[2, 1, 2\]}/bricks: [2, 1, 2], precision: float}/' bricked.yaml > floaty.yaml
expect 1 "floaty\.yaml:[0-9]+:[0-9]+: bricks: --brick: renders in double" "$bin/vri-run" --dry-run --results runs floaty.yaml
echo "bricks: ok"

