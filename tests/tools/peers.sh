#!/usr/bin/env bash
# vri-peer-vtk: VTK's ray casters on vri's scene. A tiny volume (zero on its faces, an off-centre blob on a ramp)
# rendered through the adapter must match vri-reference's exact image far better than it matches the exact image
# of each scene-match mistake: the volume flipped in y (VTK's reader, row 0 at the bottom), the node convention
# (placement: VTK's points at origin + i spacing), twice the extinction (opacity unit distance), a wider view
# angle (horizontal against vertical). Also: the stats are a render's for vri-tabulate, frames are repeated.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
bin=$VRI_BIN
/usr/bin/python3 -c 'import vtk, numpy, OpenImageIO, yaml' 2>/dev/null ||
    { echo "python3-vtk9, python3-numpy, python3-openimageio or python3-yaml not installed: skipping"; exit 77; }
command -v xvfb-run >/dev/null || [ -n "${DISPLAY:-}" ] || { echo "no X display and no xvfb-run (xvfb): skipping"; exit 77; }

source "$(dirname "${BASH_SOURCE[0]}")/lib/peer_scene.sh" && write_peer_scene
sed 's/0.08]/0.16]/; s/0.3]$/0.6]/; s/0.5]$/1.0]/' tf.yaml > tau2.yaml
camera=(--size 96x72 --eye 16,21,-22 --target 6,6,6 --up 0,1,0)

"$bin/vri-reference" --volume vol_12x12x12_uint8.raw --tf tf.yaml "${camera[@]}" --fov 35 -q -o exact.exr
"$bin/vri-reference" --volume flip_12x12x12_uint8.raw --tf tf.yaml "${camera[@]}" --fov 35 -q -o flipped.exr
"$bin/vri-reference" --volume vol_12x12x12_uint8.raw --convention node --tf tf.yaml "${camera[@]}" --fov 35 -q -o node.exr
"$bin/vri-reference" --volume vol_12x12x12_uint8.raw --tf tau2.yaml "${camera[@]}" --fov 35 -q -o tau2.exr
"$bin/vri-reference" --volume vol_12x12x12_uint8.raw --tf tf.yaml "${camera[@]}" --fov 45 -q -o fov.exr

# The worst channel's RMSE of an image against a reference, from vri-diff's JSON.
rmse() {
  "$bin/vri-diff" "$1" "$2" --failpercent 100 --warnpercent 100 --json - |
    /usr/bin/python3 -c 'import json, sys; print(max(c["rmse"] for c in json.load(sys.stdin)["channels"]))'
}
# Each mistake must be at least `factor` times farther from the peer's image than the exact scene is.
check_scene() {
  local image=$1 limit=$2 factor=$3 label=$4 good bad
  good=$(rmse exact.exr "$image")
  /usr/bin/python3 -c "import sys; sys.exit(not $good < $limit)" || fail "$label: RMSE $good against the exact image (limit $limit)"
  for mistake in flipped node tau2 fov; do
    bad=$(rmse "$mistake.exr" "$image")
    /usr/bin/python3 -c "import sys; sys.exit(not $bad > $factor * $good)" ||
        fail "$label: as close to the $mistake scene (RMSE $bad) as to the exact one ($good)"
  done
  echo "$label: RMSE $good against the exact image"
}

peer=(--volume vol_12x12x12_uint8.raw --tf tf.yaml "${camera[@]}" --fov 35 --step 0.05 -q)
"$bin/vri-peer-vtk" "${peer[@]}" --image raycast -o raycast.exr --stats raycast.json
check_scene raycast.exr 0.005 10 "vtk-fixed-point, its 15-bit ray-cast image"
"$bin/vri-peer-vtk" "${peer[@]}" -o display.exr --png display.png --stats display.json
check_scene display.exr 0.03 4 "vtk-fixed-point, the 8-bit frame shown (display resampling)"
"$bin/vri-peer-vtk" "${peer[@]}" --method vtk-gpu -o gpu.exr --stats gpu.json
check_scene gpu.exr 0.005 10 "vtk-gpu"

# 8 bits per channel in the frame shown: every value is k / 255.
/usr/bin/python3 -c '
import sys, numpy as np, OpenImageIO as oiio
v = oiio.ImageBuf(sys.argv[1]).get_pixels(oiio.FLOAT) * 255
sys.exit(not np.allclose(v, np.round(v), atol=1e-3))' display.exr || fail "the displayed frame is not 8-bit"

# The stats: a render's shape (timing median of 3 after a warm-up, threads, VTK version, mapper, step).
/usr/bin/python3 - raycast.json gpu.json <<'EOF' || fail "stats: $(cat raycast.json)"
import json, statistics, sys
for path, mapper in zip(sys.argv[1:], ["vtkFixedPointVolumeRayCastMapper", "vtkOpenGLGPUVolumeRayCastMapper"]):
    s = json.load(open(path))
    t = s["timing"]
    assert s["tool"] == "vri-peer-vtk" and s["build"]["vtk"].startswith("9."), s["build"]
    assert t["repeats"] == 3 and t["warm_up"] == 1 and len(t["wall_seconds"]) == 3
    assert t["median_wall_seconds"] == statistics.median(t["wall_seconds"]) > 0
    assert s["options"]["mapper"] == mapper and s["options"]["step_voxels"] == 0.05
    assert s["camera"]["fov_y_degrees"] == 35 and s["scene"]["box_hi"] == [12, 12, 12]
    assert s["stats"]["frames_differing"] == 0 and s["stats"]["nonfinite_pixels"] == 0
    assert len(s["transfer_function"]["points_s_r_g_b_tau"]) == 256  # one per raw value
    assert len(s["inputs"]) == 2 and all(len(i["sha512"]) == 128 for i in s["inputs"])
assert json.load(open(sys.argv[1]))["stats"]["threads"] >= 1
EOF
"$bin/vri-diff" exact.exr raycast.exr --threshold 0.01,0.001 --failpercent 100 --warnpercent 100 --json diff.json
"$bin/vri-tabulate" --layout tradeoff --run vtk raycast.json diff.json -o speed.md --csv speed.csv
grep -q '^vtk,' speed.csv || fail "vri-tabulate's tradeoff has no row for the peer: $(cat speed.csv)"
# The adapter as an outside renderer: vri-outside writes the card, the adapter reads it (--card), and the image
# is the adapter's own on the same scene, bit for bit; its stats are the outside-renderer record.
"$bin/vri-peer-vtk" --volume vol_12x12x12_uint8.raw --tf tf.yaml "${camera[@]}" --fov 35 --step 0.5 --repeat 1 -q \
  -o direct.exr
"$bin/vri-outside" --volume vol_12x12x12_uint8.raw --tf tf.yaml "${camera[@]}" --fov 35 --step 0.5 -q -o card.exr \
  --stats card.json -- "$bin/vri-peer-vtk" --card {card} --repeat 1 -q -o {output} --stats {stats}
"$bin/vri-diff" direct.exr card.exr --fail 0 > /dev/null || fail "the adapter on the card differs from its own run"
/usr/bin/python3 - card.json <<'EOF'
import json, sys
r = json.load(open(sys.argv[1]))
assert r["renderer"]["name"] == "VTK vtkFixedPointVolumeRayCastMapper" and r["renderer"]["version"].startswith("9.")
assert r["timing"]["timed"] == "frame" and r["stats"]["quantisation"] == "8-bit", (r["timing"], r["stats"])
EOF
set +e
"$bin/vri-peer-vtk" --card c.json --volume vol_12x12x12_uint8.raw -o x.exr 2> err.txt; rc=$?
set -e
[ "$rc" -eq 64 ] && grep -q "^vri-peer-vtk: error: --card: --volume would override the card's scene" err.txt ||
  fail "--card with --volume: exit $rc, $(cat err.txt)"
echo "peers: all checks passed"
