#!/usr/bin/env bash
# vri-render --method exact: the same image and bounds as vri-reference at the same tolerance, its error
# bound in the stats, a looser tolerance walking fewer pieces within the sum of both bounds.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
command -v python3 >/dev/null || { echo "python3 not installed: skipping"; exit 77; }
bin=$VRI_BIN
source "$(dirname "${BASH_SOURCE[0]}")/lib/blob.sh" && write_blob_scene

stat() { /usr/bin/python3 -c 'import json, sys; s = json.load(open(sys.argv[1]))["stats"]; print(eval(sys.argv[2]))' "$@"; }
blob=(--volume blob_8x8x8_uint8.raw --spacing 1,0.75,1 --tf tf.yaml --size 40x30 -q)

"$bin/vri-render" "${blob[@]}" --method exact --tolerance 1e-12 -o render.exr --stats render.json
"$bin/vri-reference" "${blob[@]}" --tolerance 1e-12 -o reference.exr --stats reference.json
"$bin/vri-diff" render.exr reference.exr --fail 0 > /dev/null || fail "vri-render --method exact differs from vri-reference"
grep -q '"method": "exact"' render.json || fail "stats do not name the exact method: $(cat render.json)"
[ "$(stat render.json 's["error_bound"]["max"]')" = "$(stat reference.json 's["error_bound"]["max"]')" ] ||
    fail "the error bounds of vri-render and vri-reference differ"
[ "$(stat render.json 'max(s["error_bound"]["max"]) < 1e-10')" = True ] || fail "bound $(stat render.json 's["error_bound"]')"

# The default tolerance (1e-7): fewer integrand evaluations, and the images within the sum of both bounds.
"$bin/vri-render" "${blob[@]}" --method exact -o loose.exr --stats loose.json
grep -q '"tolerance": 1e-07' loose.json || fail "default tolerance not 1e-7: $(cat loose.json)"
[ "$(stat loose.json 's["quadrature_nodes"]')" -lt "$(stat render.json 's["quadrature_nodes"]')" ] ||
    fail "a looser tolerance did not evaluate fewer nodes"
limit=$(/usr/bin/python3 -c 'import json, sys; a, b = (json.load(open(f))["stats"]["error_bound"]["stored_max"] for f in sys.argv[1:]);
print(max(x + y for x, y in zip(a, b)))' loose.json render.json)  # the bounds of the stored float32 values
"$bin/vri-diff" loose.exr render.exr --fail "$limit" --warn "$limit" > /dev/null || fail "1e-7 image beyond $limit"

# The bound is for the double value, and the stats say so; stored_max bounds the EXR's float32 values: at
# 1e-12 their rounding dwarfs the double's bound. --error-image holds that bound per pixel.
[ "$(stat render.json 's["error_bound"]["applies_to"]')" = "double value before float32 rounding" ] ||
    fail "stats do not say what the bound applies to: $(stat render.json 's["error_bound"]')"
[ "$(stat render.json 'all(m < r and r <= t <= m + r + 1e-9 for m, r, t in zip(s["error_bound"]["max"],
    s["error_bound"]["float32_rounding_max"], s["error_bound"]["stored_max"]))')" = True ] ||
    fail "stored_max is not the double's bound plus the float32 rounding: $(stat render.json 's["error_bound"]')"
"$bin/vri-render" "${blob[@]}" --method exact --tolerance 1e-12 -o again.exr --error-image bound.exr
printf 'points:\n  - [0.0, 0.0, 0.0, 0.0, 0.0]\n' > zero.yaml  # an image of zeros, to read the bounds through vri-diff
"$bin/vri-render" --volume blob_8x8x8_uint8.raw --spacing 1,0.75,1 --tf zero.yaml --size 40x30 -q --method exact -o zero.exr
"$bin/vri-diff" bound.exr zero.exr --json diff.json > /dev/null || true
/usr/bin/python3 - render.json diff.json <<'PY' || fail "the error image's largest values are not stored_max"
import json, sys
stored = json.load(open(sys.argv[1]))["stats"]["error_bound"]["stored_max"]
image = [c["max_abs"] for c in json.load(open(sys.argv[2]))["channels"]]
assert image == stored, (image, stored)
PY

# The same with every brick walked (the unit tests count the pieces skipped): not one bit changes.
"$bin/vri-render" "${blob[@]}" --method exact --no-skip-empty -o all.exr --stats all.json
"$bin/vri-diff" all.exr loose.exr --fail 0 > /dev/null || fail "--no-skip-empty changed the exact image"
# --max-error E: a pixel bound asked for directly. The default tolerance's bound is above 1e-9 here; asked for
# 1e-9, both tools search a tolerance whose largest bound is at most that, record it, and give the image that
# tolerance gives when asked for directly.
[ "$(stat loose.json 'max(s["error_bound"]["max"]) > 1e-9')" = True ] || fail "the default bound is already below 1e-9"
for tool in vri-render vri-reference; do
    method=(); [ "$tool" = vri-render ] && method=(--method exact)
    "$bin/$tool" "${blob[@]}" "${method[@]}" --max-error 1e-9 -o max-error.exr --stats max-error.json
    [ "$(stat max-error.json 'max(s["error_bound"]["max"]) <= 1e-9')" = True ] ||
        fail "$tool --max-error 1e-9: bound $(stat max-error.json 's["error_bound"]["max"]')"
    found=$(/usr/bin/python3 -c 'import json, sys; o = json.load(open(sys.argv[1]))["options"]; print(o["max_error"], repr(o["tolerance"]))' max-error.json)
    [ "${found%% *}" = 1e-09 ] || fail "$tool: the stats do not record max_error: $found"
    "$bin/$tool" "${blob[@]}" "${method[@]}" --tolerance "${found#* }" -o direct.exr
    "$bin/vri-diff" direct.exr max-error.exr --fail 0 > /dev/null || fail "$tool: --max-error's image is not its tolerance's"
done
# From 128 pixels a side a pilot at a quarter of each side finds the tolerance first; the image's accepted
# render is the output, not rendered again (the stats list every render; a second timed frame is rendered and
# must equal it bit for bit), and it is the image that tolerance gives when asked for directly.
big=(--volume blob_8x8x8_uint8.raw --spacing 1,0.75,1 --tf tf.yaml --size 160x128 -q --method exact)
"$bin/vri-render" "${big[@]}" --max-error 1e-9 --repeat 2 -o pilot.exr --error-image pilot-bound.exr --stats pilot.json
check=$(/usr/bin/python3 - pilot.json <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
renders = d["stats"]["max_error_search"]["renders"]
ok = (renders[0]["what"] == "pilot" and renders[0]["size"] == "40x32" and renders[-1]["what"] == "image"
      and renders[-1]["size"] == "160x128" and renders[-1]["bound"] <= 1e-9
      and renders[-1]["tolerance"] == d["options"]["tolerance"] and max(d["stats"]["error_bound"]["max"]) <= 1e-9
      and all(r["what"] == "pilot" for r in renders[:-1]) and d["stats"]["max_error_search"]["max_error"] == 1e-9)
print(("ok " + repr(d["options"]["tolerance"])) if ok else "bad " + json.dumps(renders))
PY
)
[ "${check%% *}" = ok ] || fail "--max-error's search record: $check"
"$bin/vri-render" "${big[@]}" --tolerance "${check#* }" -o pilot-direct.exr --error-image pilot-direct-bound.exr
"$bin/vri-diff" pilot-direct.exr pilot.exr --fail 0 > /dev/null || fail "--max-error's image (from the pilot) is not its tolerance's"
"$bin/vri-diff" pilot-direct-bound.exr pilot-bound.exr --fail 0 > /dev/null || fail "--max-error's bounds are not its tolerance's"
# A zoom centre on the frame's right edge is on the pilot's too (scaled without rounding past it).
"$bin/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 169x128 -q --method exact --zoom 2 --zoom-centre 169,64 --max-error 1e-6 -o zoom-edge.exr ||
    fail "--max-error with a zoom centre on the frame's edge"
# TF points where an 8-bit volume's constant regions sit (a pulse 1e-9 wide from raw value 1, a jump at 3,
# spelled k/255 as a TF file holds them): a cell whose corners hold one value is exact, and beside a face
# whose corners sit on a point s's side of it is known from the face's opposite corners (constant_face.h),
# so the largest bound, about 0.72 when such pieces counted whole and 2.6e-6 while only bisection on s found
# their windows, is some 4e-7 (a ray tangent to the iso-surface of 1/255 near a face of zeros): --max-error
# 1e-6 is within reach, and few rays need a whole-sub-piece window.
/usr/bin/python3 - <<'PY'
import random
random.seed(11)
blocks = [random.choice([0, 1, 3, 100]) for _ in range(64)]
voxels = bytes(blocks[x // 3 + 4 * (y // 3) + 16 * (z // 3)] for z in range(12) for y in range(12) for x in range(12))
open("blocks_12x12x12_uint8.raw", "wb").write(voxels)
a, b = repr(1 / 255), repr(1 / 255 + 1e-9)
open("points.yaml", "w").write(f"""points:
  - [0.0, 0.0, 0.0, 0.0, 0.0]
  - [{a}, 0.0, 0.0, 0.0, 0.0]
  - [{a}, 0.9, 0.5, 0.2, 0.3]
  - [{b}, 0.3, 0.6, 1.0, 0.3]
  - [{b}, 0.0, 0.0, 0.0, 0.0]
  - [{repr(3 / 255)}, 0.0, 0.0, 0.0, 0.0]
  - [{repr(3 / 255)}, 1.0, 0.4, 0.7, 0.5]
  - [1.0, 0.5, 1.0, 0.1, 0.5]
""")
PY
"$bin/vri-render" --volume blocks_12x12x12_uint8.raw --tf points.yaml --size 40x30 --eye 4.5,4.5,40 --target 4.5,4.5,0 \
    --fov 20 -q --method exact --max-error 1e-6 -o points.exr --stats points.json || fail "--max-error 1e-6 with TF points at data values"
[ "$(stat points.json 'max(s["error_bound"]["max"]) <= 1e-6')" = True ] || fail "bound $(stat points.json 's["error_bound"]')"
[ "$(stat points.json '10 * s["rays_whole_sub_piece_window"] < s["rays_hit"]')" = True ] ||
    fail "rays with a whole-sub-piece window: $(stat points.json 's["rays_whole_sub_piece_window"]') of $(stat points.json 's["rays_hit"]')"
# At 400x300 some rays leave a face of 3s tangent to the jump's level along a whole voxel (the unit test
# "rays leaving a face that holds a TF point" has their truth): bounds of 0.82 before the faces, 4e-9 with them.
"$bin/vri-render" --volume blocks_12x12x12_uint8.raw --tf points.yaml --size 400x300 --eye 4.5,4.5,40 --target 4.5,4.5,0 \
    --fov 20 -q --method exact --tolerance 1e-12 -o points-400.exr --stats points-400.json || fail "the 400x300 render"
[ "$(stat points-400.json 'max(s["error_bound"]["max"]) <= 1e-7')" = True ] || fail "400x300: bound $(stat points-400.json 's["error_bound"]["max"]')"
if "$bin/vri-render" "${blob[@]}" --method riemann --max-error 1e-3 -o bad.exr 2> bad.txt; then fail "--max-error with riemann"; fi
grep -q "^vri-render: error: --max-error applies to --method exact only" bad.txt || fail "$(cat bad.txt)"
echo "render_exact: all checks passed"
