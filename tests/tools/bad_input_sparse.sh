#!/usr/bin/env bash
# Bad input to sparse volumes (--storage): an unknown storage, what reads dense volumes only (the exact
# method, Vulkan, writing a converted file), byte limits that the brick table or the stored bricks exceed
# (checked before either is allocated), a box whose table would overflow, and a non-finite float voxel
# found in the bricks. Each case: the exit code, one stderr line, an unchanged work directory (lib/bad_input.sh).
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
# The limit (VRI_MAX_BYTES) against the brick table (19^3 entries of 4 bytes), then against the stored bricks.
bad 1 "${R}cloud\.vdb: vri_dims 150x150x150 \(uint8\) kept sparse, its brick table: needs 27436 bytes, limit 1000 \(VRI_MAX_BYTES\)$" -- \
  env VRI_MAX_BYTES=1000 "${render[@]}" --volume cloud.vdb --storage sparse
bad 1 "${R}a sparse 150x150x150 uint8 volume \([0-9]+ stored bricks of 9\^3 voxels and the brick table\): needs [0-9]+ bytes, limit 100000 \(VRI_MAX_BYTES\)$" -- \
  env VRI_MAX_BYTES=100000 "${render[@]}" --volume cloud.vdb --storage sparse
# 2^30 voxels along each axis: the table alone would take 2^83 bytes (auto keeps such a box sparse).
bad 1 "${C}huge\.vdb: vri_dims 1073741824x1073741824x1073741824 \(uint8\) kept sparse, its brick table: needs .* bytes, limit [0-9]+ \(VRI_MAX_BYTES\)$" -- \
  "$bin/vri-convert" --info huge.vdb
bad 1 "${C}nan\.vdb: voxel \(x 17, y 1, z 2\) is nan: float volumes must hold finite values$" -- \
  "$bin/vri-convert" --info --storage sparse nan.vdb
bad_done
