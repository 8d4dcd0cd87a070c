#!/usr/bin/env bash
# Peak memory of a volume rendered whole and as bricks (docs/conventions/bricks.md): writes a synthetic N^3
# uint8 volume (a smooth blob field, never committed) into a scratch folder, renders it unbricked and as
# every brick of a B x B x B grid, joins the layers, and prints a Markdown table of each process's peak
# resident memory (GNU time's %M) against the bytes it holds, with the join's bound and largest
# difference from the unbricked image.
#   scripts/brick-memory.sh [BUILD] [N] [B] [SCRATCH]     (make bricks-memory: build 1024 2)
set -euo pipefail
build=${1:-build} n=${2:-1024} b=${3:-2} scratch=${4:-$build/bricks-memory}
for value in "$n" "$b"; do  # whole numbers before any arithmetic sees them
  [[ $value =~ ^[1-9][0-9]{0,5}$ ]] || { echo "brick-memory: N and B are whole numbers, got '$value'" >&2; exit 64; }
done
repo=$(cd "$(dirname "$0")/.." && pwd)
bin=$(cd "$build/bin" && pwd)
mkdir -p "$scratch" && cd "$scratch"
volume=blobs_${n}x${n}x${n}_uint8.raw
if [ ! -f "$volume" ]; then
  echo "brick-memory: writing $volume ($((n * n * n / 1048576)) MiB)" >&2
  /usr/bin/python3 "$repo/scripts/blob-volume.py" "$n" "$volume"
fi
cp "$repo/experiments/tf/blobs.yaml" tf.yaml
scene=(--volume "$volume" --tf tf.yaml --size 960x540 --method riemann --step 1 --no-skip-empty -q)
peak() { /usr/bin/time -f %M -o rss.txt "$@" && cat rss.txt; }   # KiB
echo "| render | volume bytes held | peak RSS (MiB) | peak / held | seconds |"
echo "|---|--:|--:|--:|--:|"
start=$(date +%s.%N)
rss=$(peak "$bin/vri-render" "${scene[@]}" -o whole.exr --stats whole.json)
held=$(/usr/bin/python3 -c 'import json; print(json.load(open("whole.json"))["scene"]["volume_bytes"])')
echo "| whole | $held | $((rss / 1024)) | $(/usr/bin/python3 -c "print(f'{$rss * 1024 / $held:.2f}')") | $(/usr/bin/python3 -c "print(f'{$(date +%s.%N) - $start:.1f}')") |"
layers=()
for ((z = 0; z < b; ++z)); do for ((y = 0; y < b; ++y)); do for ((x = 0; x < b; ++x)); do
  start=$(date +%s.%N)
  rss=$(peak "$bin/vri-render" "${scene[@]}" --bricks "$b,$b,$b" --brick "$x,$y,$z" -o "layer-$x-$y-$z.exr" \
        --stats "layer-$x-$y-$z.json")
  held=$(/usr/bin/python3 -c "import json; print(json.load(open('layer-$x-$y-$z.json'))['scene']['volume_bytes'])")
  echo "| brick $x,$y,$z of $b,$b,$b | $held | $((rss / 1024)) | $(/usr/bin/python3 -c "print(f'{$rss * 1024 / $held:.2f}')") | $(/usr/bin/python3 -c "print(f'{$(date +%s.%N) - $start:.1f}')") |"
  layers+=(--layer "layer-$x-$y-$z.exr" "layer-$x-$y-$z.json")
done; done; done
"$bin/vri-merge-tiles" "${layers[@]}" -o joined.exr --stats joined.json
/usr/bin/python3 - <<'PY'
import json
import numpy as np
import OpenImageIO as oiio
whole = oiio.ImageBuf("whole.exr").get_pixels(oiio.FLOAT).astype(np.float64)
joined = oiio.ImageBuf("joined.exr").get_pixels(oiio.FLOAT).astype(np.float64)
bound = json.load(open("joined.json"))["join"]["bound_max"]
worst = float(np.abs(whole - joined).max())
print(f"\njoined against whole: largest difference {worst:.3g}, bound {bound:.3g}, "
      f"pixels that differ {int(np.any(whole != joined, axis=2).sum())} of {whole.shape[0] * whole.shape[1]}")
assert worst <= bound
PY
