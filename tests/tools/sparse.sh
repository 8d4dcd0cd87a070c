#!/usr/bin/env bash
# Sparse volumes (--storage): a scene rendered from its stored 8^3 bricks is the dense scene's image bit for
# bit (every CPU method, both conventions, double and float; a .vdb read straight into bricks and a dense
# input converted), `vri-convert --info` summarises it without unpacking it, and a 1024^3 box that holds a
# small cloud (1 GiB dense) renders in a few tens of MB: the stats' volume_bytes and the process's peak
# memory stay far below the dense size. scripts/sparse-scene.py writes the scenes (python3-openvdb).
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
python=/usr/bin/python3
"$python" -c "import pyopenvdb, numpy" 2>/dev/null || { echo "skip: python3-openvdb or python3-numpy missing"; exit 77; }
bin="$VRI_BIN"
tf="$VRI_SOURCE/experiments/tf/bonsai.yaml"
scene() { VRI_BIN="$bin" "$python" "$VRI_SOURCE/scripts/sparse-scene.py" "$@" > /dev/null; }
json() { "$python" -c "import json, sys; j = json.load(open(sys.argv[1])); print($2)" "$1"; }

# Two clouds in a 150^3 box: bricks empty, full and cut by the box's edge (150 is no multiple of 8).
scene cloud150.vdb --box 150 --pieces 2
"$bin/vri-convert" -q cloud150.vdb cloud_150x150x150_uint8.raw
for run in riemann:cell:float riemann:node:double composite:cell:double composite:node:float simpson:cell:double \
           simpson:node:float coupled:node:double decoupled:cell:float; do
  IFS=: read -r method convention precision <<< "$run"
  opts=(--tf "$tf" --size 40x32 --method "$method" --convention "$convention" --precision "$precision" -q)
  "$bin/vri-render" --volume cloud150.vdb --storage dense "${opts[@]}" -o dense.exr --stats dense.json
  "$bin/vri-render" --volume cloud150.vdb --storage sparse "${opts[@]}" -o sparse.exr --stats sparse.json
  "$bin/vri-render" --volume cloud_150x150x150_uint8.raw --storage sparse "${opts[@]}" -o converted.exr
  for image in sparse converted; do
    "$bin/vri-diff" dense.exr $image.exr --fail 0 > diff.txt ||
      fail "$run: the $image render differs from the dense one: $(tail -3 diff.txt)"
  done
  [ "$(json sparse.json "j['scene']['storage']")" = sparse ] || fail "$run: sparse.json's storage is not sparse"
  [ "$(json sparse.json "j['stats']['samples_evaluated']")" -gt 0 ] || fail "$run: no sample evaluated"
done
# The packet engine reads dense volumes only: a sparse float Riemann render takes the scalar path.
"$bin/vri-render" --volume cloud150.vdb --storage sparse --tf "$tf" --size 8x8 --precision float -q -o f.exr --stats f.json
[ "$(json f.json "j['stats']['simd_target']")" = None ] || fail "a sparse render ran the packet engine"

# --info without unpacking: the same summary as the dense one, and what the sparse copy holds.
"$bin/vri-convert" --info --json --storage dense cloud150.vdb > dense_info.json
"$bin/vri-convert" --info --json --storage sparse cloud150.vdb > sparse_info.json
for field in active_voxels active_bricks bricks data_range histogram zero_fraction; do
  [ "$(json dense_info.json "j['$field']")" = "$(json sparse_info.json "j['$field']")" ] ||
    fail "--info $field: sparse $(json sparse_info.json "j['$field']"), dense $(json dense_info.json "j['$field']")"
done
[ "$(json sparse_info.json "j['stored_bricks'] >= j['active_bricks'] > 0")" = True ] || fail "stored bricks: $(cat sparse_info.json)"
[ "$(json sparse_info.json "j['bytes'] < j['dims'][0] ** 3")" = True ] || fail "sparse bytes: $(cat sparse_info.json)"

# One cloud in a 1024^3 box: 1 GiB dense, kept sparse by --storage auto (the dense box would be more
# than 1024 times the file), never unpacked. Peak memory is the process's (GNU time), in KiB.
scene cloud1024.vdb --box 1024 --pieces 1
"$bin/vri-convert" --info --json cloud1024.vdb > info1024.json
[ "$(json info1024.json "j['storage']")" = sparse ] || fail "--storage auto unpacked a 1024^3 box of one cloud"
[ "$(json info1024.json "j['bricks']")" = 2097152 ] || fail "--info bricks: $(json info1024.json "j['bricks']")"
command -v /usr/bin/time > /dev/null || { echo "skip: GNU time missing for the peak memory"; exit 77; }
/usr/bin/time -f %M -o peak.txt "$bin/vri-render" --volume cloud1024.vdb --tf "$tf" --size 96x96 -q -o big.exr \
  --stats big.json
[ "$(json big.json "j['scene']['storage']")" = sparse ] || fail "the 1024^3 render was not sparse"
[ "$(json big.json "j['scene']['volume_bytes'] < 32 * 2**20")" = True ] ||
  fail "the sparse 1024^3 volume holds $(json big.json "j['scene']['volume_bytes']") bytes"
[ "$(tail -1 peak.txt)" -lt 400000 ] || fail "the sparse 1024^3 render peaked at $(tail -1 peak.txt) KiB (dense: 1 GiB)"
[ "$(json big.json "j['stats']['rays_hit']")" -gt 0 ] || fail "the 1024^3 render hit nothing"
echo "sparse: bitwise equal to dense; 1024^3 box in $(json big.json "j['scene']['volume_bytes']") bytes, peak $(tail -1 peak.txt) KiB"
