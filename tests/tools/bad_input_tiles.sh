#!/usr/bin/env bash
# Bad input to --region (vri-render, vri-reference) and to vri-merge-tiles: one line naming the option
# or file and what was expected, exit 64 for what the command line gets wrong, 1 for tiles that do not
# make up one image, nothing written.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
source "$(dirname "${BASH_SOURCE[0]}")/lib/bad_input.sh"
bin=${VRI_BIN:?}
source "$(dirname "${BASH_SOURCE[0]}")/lib/blob.sh" && write_blob_scene
scene=(--volume blob_8x8x8_uint8.raw --tf tf.yaml --size 8x6 -q)
E="^vri-render: error: "
R="${E}--region: expected a pixel rectangle X,Y,WIDTH,HEIGHT \(integers, X and Y >= 0, WIDTH and HEIGHT >= 1, X \+ WIDTH and Y \+ HEIGHT below 2\^31\), got"

for region in 1,2,3 1,2,3,4,5 a,0,1,1 0,0,0,6 0,0,8,-1 -1,0,1,1 1.5,0,1,1 2147483647,0,1,1 0,99999999999,1,1 ''; do
  bad 64 "$R '$region'$" -- "$bin/vri-render" "${scene[@]}" --region "$region" -o out.exr
done
bad 64 "${E}--region: 4,0,5,6 reaches outside the 8x6 image of --size \(expected X \+ WIDTH <= 8 and Y \+ HEIGHT <= 6\)$" \
  -- "$bin/vri-render" "${scene[@]}" --region 4,0,5,6 -o out.exr --stats out.json
bad 64 "^vri-reference: error: --region: 0,6,1,1 reaches outside the 8x6 image of --size" \
  -- "$bin/vri-reference" "${scene[@]}" --region 0,6,1,1 -o out.exr
bad 64 "^vri-reference: error: --region: expected a pixel rectangle" \
  -- "$bin/vri-reference" "${scene[@]}" --region 0,0,1 -o out.exr
bad 1 "${E}the logged pixel 1,5 is outside the region 0,0,8,3 of the 8x6 image$" \
  -- "$bin/vri-render" "${scene[@]}" --region 0,0,8,3 --method coupled --log-ray 1,5 --log ray.csv -o out.exr

# Tiles to merge, and tiles that do not go together.
"$bin/vri-render" "${scene[@]}" --region 0,0,8,3 -o t1.exr --stats t1.json
"$bin/vri-render" "${scene[@]}" --region 0,3,8,3 -o t2.exr --stats t2.json
"$bin/vri-render" "${scene[@]}" --region 0,2,8,4 -o t3.exr --stats t3.json
"$bin/vri-render" "${scene[@]}" --region 0,3,8,3 --step 0.25 -o step.exr --stats step.json
"$bin/vri-render" "${scene[@]}" --region 0,3,8,3 --repeat 2 -o twice.exr --stats twice.json
"$bin/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 8x7 -q --region 0,3,8,3 -o big.exr --stats big.json
"$bin/vri-render" "${scene[@]}" -o whole.exr --stats whole.json
# Stats edited by hand (issue 48, classes 5 and 7): a camera of 30000 x 30000 that one region covers, which once
# made vri-merge-tiles allocate 17.6 GB before it read a tile; numbers that no int holds.
/usr/bin/python3 - <<'PY'
import json
t = json.load(open("t1.json"))
t["camera"]["width"] = t["camera"]["height"] = 30000
t["region"] = {"x": 0, "y": 0, "width": 30000, "height": 30000}
json.dump(t, open("huge.json", "w"))
for key, value in (("x", 1e300), ("width", 2.5), ("y", "0"), ("height", -3)):
    t = json.load(open("t1.json")); t["region"][key] = value
    json.dump(t, open(f"forged-{key}.json", "w"))
for key, value in (("rays", 1e308), ("wall_seconds", -5)):
    t = json.load(open("t2.json")); t["stats"][key] = value
    json.dump(t, open(f"forged-{key}.json", "w"))
PY
M="^vri-merge-tiles: error: "
merge=("$bin/vri-merge-tiles")
bad 64 "${M}Exactly 1 option from \[--tile,--layer\] is required \(" -- "${merge[@]}" -o out.exr
bad 64 "${M}Exactly 1 option from \[--tile,--layer\] is required and 2 were given" -- "${merge[@]}" --tile t1.exr t1.json --layer t2.exr t2.json -o out.exr
bad 64 "${M}--tile: expected IMAGE\.exr STATS\.json, got 1 word \(see --help\)$" -- "${merge[@]}" --tile t1.exr -o out.exr
bad 64 "${M}-o: 'out.png' is not an .exr file" -- "${merge[@]}" --tile t1.exr t1.json --tile t2.exr t2.json -o out.png
bad 64 "${M}--stats: 'out.exr' is also -o's output$" -- "${merge[@]}" --tile t1.exr t1.json -o out.exr --stats out.exr
bad 1 "${M}missing.json: no such file" -- "${merge[@]}" --tile t1.exr t1.json --tile t2.exr missing.json -o out.exr
bad 1 "${M}t3.json: region 0,2,8,4 overlaps t1.json's region 0,0,8,3 at pixel 0,2 \(tiles must cover the image once\)$" \
  -- "${merge[@]}" --tile t1.exr t1.json --tile t3.exr t3.json -o out.exr
bad 1 "${M}the tiles cover 24 of the 8x6 image's 48 pixels \(tiles must cover the image once\)$" \
  -- "${merge[@]}" --tile t1.exr t1.json -o out.exr
bad 1 "${M}t1.json: region 0,0,8,3 overlaps t1.json's region 0,0,8,3 at pixel 0,0" \
  -- "${merge[@]}" --tile t1.exr t1.json --tile t1.exr t1.json --tile t2.exr t2.json -o out.exr
bad 1 "${M}step.json: its \"options\" differs from t1.json's \(the tiles of one image share tool, build, inputs, scene, transfer function, camera and options\)$" \
  -- "${merge[@]}" --tile t1.exr t1.json --tile step.exr step.json -o out.exr
bad 1 "${M}big.json: its \"camera\" differs from t1.json's" -- "${merge[@]}" --tile t1.exr t1.json --tile big.exr big.json -o out.exr
bad 1 "${M}twice.json: timing.repeats is 2, but t1.json has 1 \(the tiles of one image must agree in it\)$" \
  -- "${merge[@]}" --tile t1.exr t1.json --tile twice.exr twice.json -o out.exr
bad 1 "${M}whole.json: has no \"region\" \(not a tile: render one with --region X,Y,WIDTH,HEIGHT\)$" \
  -- "${merge[@]}" --tile whole.exr whole.json -o out.exr
bad 1 "${M}t2.exr: its vri:region is '0,3,8,3', but t1.json says 0,0,8,3 \(an image and stats of different tiles\?\)$" \
  -- "${merge[@]}" --tile t2.exr t1.json --tile t1.exr t2.json -o out.exr
bad 1 "${M}t3.exr: a 8x4 image of 4 channels, but t2.json says a RGBA region 0,3,8,3$" \
  -- "${merge[@]}" --tile t1.exr t1.json --tile t3.exr t2.json -o out.exr
bad 1 "${M}tf.yaml: " -- "${merge[@]}" --tile t1.exr tf.yaml -o out.exr
bad 1 "${M}t1.exr: a 8x3 image of 4 channels, but huge.json says a RGBA region 0,0,30000,30000$" \
  -- "${merge[@]}" --tile t1.exr huge.json -o out.exr
bad 1 "${M}forged-x.json: region.x: expected a whole number in \[0, 2147483647\], got 1e\+300$" \
  -- "${merge[@]}" --tile t1.exr forged-x.json -o out.exr
bad 1 "${M}forged-width.json: region.width: expected a whole number in \[1, 2147483647\], got 2.5$" \
  -- "${merge[@]}" --tile t1.exr forged-width.json -o out.exr
bad 1 "${M}forged-y.json: region.y: expected a whole number in \[0, 2147483647\], got \"0\"$" \
  -- "${merge[@]}" --tile t1.exr forged-y.json -o out.exr
bad 1 "${M}forged-rays.json: stats.rays: expected a whole number in \[0, 9007199254740992\], got 1e\+308$" \
  -- "${merge[@]}" --tile t1.exr t1.json --tile t2.exr forged-rays.json -o out.exr
bad 1 "${M}forged-wall_seconds.json: stats.wall_seconds: expected a count or a time in \[0, 2\^53\], got -5$" \
  -- "${merge[@]}" --tile t1.exr t1.json --tile t2.exr forged-wall_seconds.json -o out.exr
bad 1 "${M}forged-height.json: region.height: expected a whole number in \[1, 2147483647\], got -3$" \
  -- "${merge[@]}" --tile t1.exr forged-height.json -o out.exr
# Tiles of a --max-error render each searched their own pixels: the message says so.
"$bin/vri-reference" "${scene[@]}" --region 0,0,8,3 --max-error 1e-9 -o m1.exr --stats m1.json
"$bin/vri-reference" "${scene[@]}" --region 0,3,8,3 --max-error 1e-9 -o m2.exr --stats m2.json
bad 1 "${M}m2.json: found tolerance .* for --max-error 1e-09 where m1.json found .* \(each tile searched its own pixels\): render the tiles with one --tolerance" \
  -- "${merge[@]}" --tile m1.exr m1.json --tile m2.exr m2.json -o out.exr
bad_done
