#!/usr/bin/env bash
# Bad input to sparse volumes (--storage): an unknown storage, what reads dense volumes only (the exact
# method, Vulkan, writing a converted file), byte limits that the brick table or the stored bricks exceed
# (checked before either is allocated), a box whose table would overflow, a non-finite float voxel found in
# the bricks, and files of a few KB whose tiles fill gigabytes of bricks (issue 29 item 4: the bricks that
# tiles fill are counted before any is read). Each case: the exit code, one stderr line, an unchanged work
# directory (lib/bad_input.sh) and a peak resident memory under 256 MiB (GNU time).
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
source "$(dirname "${BASH_SOURCE[0]}")/lib/bad_input.sh"
python=/usr/bin/python3
"$python" -c "import pyopenvdb, numpy" 2>/dev/null || { echo "skip: python3-openvdb or python3-numpy missing"; exit 77; }
bin="$VRI_BIN"
tf="$VRI_SOURCE/experiments/tf/bonsai.yaml"
R='^vri-render: error: '
C='^vri-convert: error: '

# --- inputs, made before the cases: the work directory must stay as it is from here on ---
VRI_BIN="$bin" "$python" "$VRI_SOURCE/scripts/sparse-scene.py" cloud.vdb --box 150 --pieces 2 > /dev/null
"$python" - <<'PY'
import numpy as np, pyopenvdb as vdb
grid = vdb.read("cloud.vdb", "density")
grid.metadata = {**grid.metadata, "vri_dims": (1 << 30, 1 << 30, 1 << 30)}
vdb.write("huge.vdb", grids=[grid])
nan = vdb.FloatGrid()
nan.name = "density"
nan.copyFromArray(np.ones((20, 3, 3), np.float32), ijk=(0, 0, 0), tolerance=0)
nan.getAccessor().setValueOn((17, 1, 2), float("nan"))
vdb.write("nan.vdb", grids=[nan])
# One active value over a cube of N^3 voxels, a few KB on disk: OpenVDB keeps it as tiles of 128^3
# (a node's tiles), or as one tile of the root's 4096^3 when the cube is one.
def cube(name, n, value=1.0, metadata=None, lo=(0, 0, 0)):
    grid = vdb.FloatGrid()
    grid.name = "density"
    grid.fill(lo, tuple(c + n - 1 for c in lo), value, True)
    if metadata:
        grid.metadata = metadata
    vdb.write(name, grids=[grid])
cube("tile512.vdb", 512)
cube("tile1024.vdb", 1024)
cube("tile2048.vdb", 2048)
cube("root.vdb", 4096)
cube("uint8.vdb", 2048, 7.0, {"vri_voxel_type": "uint8", "vri_dims": (2048, 2048, 2048), "vri_format_version": 2})
cube("offset.vdb", 1024, lo=(-1024, 128, 4096))  # tiles off the origin
cube("small.vdb", 64)
PY

render=("$bin/vri-render" --tf "$tf" --size 8x8 -q -o out.exr)
bad 1 "${R}--storage: unknown storage 'packed' \(expected dense, sparse or auto\)$" -- "${render[@]}" --volume cloud.vdb --storage packed
bad 1 "${R}--method exact renders dense volumes only, and the volume is kept sparse .*: use --storage dense$" -- \
  "${render[@]}" --volume cloud.vdb --storage sparse --method exact
if built_with_vulkan; then
  bad 1 "${R}--backend vulkan renders dense volumes only, .*: use --storage dense$" -- \
    "${render[@]}" --volume cloud.vdb --storage sparse --backend vulkan
fi
bad 1 "${C}cloud\.vdb: kept sparse \(--storage sparse\), which only --info reads: convert with --storage dense$" -- \
  "$bin/vri-convert" --storage sparse cloud.vdb out.raw
# The limit (VRI_MAX_BYTES) against the brick table (19^3 entries of 4 bytes), then against the bricks that
# the grid's leaves and tiles fill, counted before any is read.
bad 1 "${R}cloud\.vdb: vri_dims 150x150x150 \(uint8\) kept sparse, its brick table: needs 27436 bytes, limit 1000 \(VRI_MAX_BYTES\)$" -- \
  env VRI_MAX_BYTES=1000 "${render[@]}" --volume cloud.vdb --storage sparse
bad 1 "${R}cloud\.vdb: vri_dims 150x150x150 \(uint8\) kept sparse, the [0-9]+ bricks that its tiles and leaves fill: needs [0-9]+ bytes, limit 100000 \(VRI_MAX_BYTES\)$" -- \
  env VRI_MAX_BYTES=100000 "${render[@]}" --volume cloud.vdb --storage sparse
# 2^30 voxels along each axis: the table alone would take 2^83 bytes (auto keeps such a box sparse).
bad 1 "${C}huge\.vdb: vri_dims 1073741824x1073741824x1073741824 \(uint8\) kept sparse, its brick table: needs .* bytes, limit [0-9]+ \(VRI_MAX_BYTES\)$" -- \
  "$bin/vri-convert" --info huge.vdb
bad 1 "${C}nan\.vdb: voxel 157 \(x 17, y 1, z 2\) is nan: float volumes must hold finite values$" -- \
  "$bin/vri-convert" --info --storage sparse nan.vdb

# --- item 4: tiles that fill gigabytes of bricks, refused before any brick is read ---
fill='kept sparse, the ([0-9]+) bricks that its tiles and leaves fill: needs [0-9]+ bytes'
ratio='limit 268435456 for a file of [0-9]+ bytes \(1024 times its size or 256 MiB; set VRI_MAX_BYTES to allow more\)$'
bad 1 "${C}tile512\.vdb: active voxels 512x512x512 \(float32\) ${fill/([0-9]+)/262144}, $ratio" -- timeout 20 "$bin/vri-convert" --info tile512.vdb
bad 1 "${C}tile1024\.vdb: active voxels 1024x1024x1024 \(float32\) ${fill/([0-9]+)/2097152}, $ratio" -- timeout 20 "$bin/vri-convert" --info tile1024.vdb
bad 1 "${C}tile1024\.vdb: active voxels 1024x1024x1024 \(float32\) $fill, $ratio" -- timeout 20 "$bin/vri-convert" --info --storage sparse tile1024.vdb
bad 1 "${C}tile2048\.vdb: active voxels 2048x2048x2048 \(float32\) ${fill/([0-9]+)/16777216}, limit 17179869184 \(VRI_MAX_BYTES\)$" -- timeout 20 "$bin/vri-convert" --info tile2048.vdb
bad 1 "${C}uint8\.vdb: vri_dims 2048x2048x2048 \(uint8\) ${fill/([0-9]+)/16777216}, $ratio" -- timeout 20 "$bin/vri-convert" --info uint8.vdb
bad 1 "${C}offset\.vdb: active voxels 1024x1024x1024 \(float32\) $fill, $ratio" -- timeout 20 "$bin/vri-convert" --info offset.vdb
# The root's tile of 4096^3: its brick table alone is over the ratio; with a stated limit that holds the
# table (512 MiB), the bricks are refused all the same, without reading one.
bad 1 "${C}root\.vdb: active voxels 4096x4096x4096 \(float32\) kept sparse, its brick table: needs 536870912 bytes, $ratio" -- timeout 20 "$bin/vri-convert" --info root.vdb
bad 1 "${C}root\.vdb: active voxels 4096x4096x4096 \(float32\) ${fill/([0-9]+)/134217728}, limit 600000000 \(VRI_MAX_BYTES\)$" -- env VRI_MAX_BYTES=600000000 timeout 20 "$bin/vri-convert" --info root.vdb
bad 1 "${C}tile1024\.vdb: active voxels 1024x1024x1024 \(float32\): needs 4294967296 bytes, $ratio" -- timeout 20 "$bin/vri-convert" --info --storage dense tile1024.vdb
bad 1 "${R}tile1024\.vdb: active voxels 1024x1024x1024 \(float32\) $fill" -- timeout 20 "${render[@]}" --volume tile1024.vdb
bad 1 "^vri-reference: error: tile2048\.vdb: active voxels 2048x2048x2048 \(float32\) $fill" -- timeout 20 "$bin/vri-reference" --volume tile2048.vdb --tf "$tf" --size 8x8 -q -o out.exr
# A tile within the limits reads, sparse or dense, as the cube it is.
for storage in sparse dense; do
  "$bin/vri-convert" --info --json --storage $storage small.vdb | "$python" -c '
import json, sys
info = json.load(sys.stdin)
assert info["dims"] == [64, 64, 64] and info["active_voxels"] == 64 ** 3, info' || fail "small.vdb --storage $storage"
done

bad_done
