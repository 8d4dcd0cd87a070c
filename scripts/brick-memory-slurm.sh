#!/usr/bin/env bash
# A volume larger than a Slurm job may hold, rendered as bricks through vri-run --executor slurm on a test
# cluster of this machine (tests/tools/lib/slurm_cluster.sh: two slurmd of one core each, memory enforced by
# jobacct_gather's OverMemoryKill), each brick's job given LIMIT MiB by a site profile, less than the whole
# volume: writes a
# synthetic N^3 uint8 volume (scripts/blob-volume.py, never committed), renders it whole with the local
# executor (this machine's memory) and as B x B x B bricks on the cluster, and prints a Markdown table of each
# job's peak resident memory (the manifest's peak_rss_mib) against what it holds (its brick with the ghost
# layer, and its layer image), with the joined image's difference from the whole one against the join's bound.
# Needs root (slurmd); the cluster is stopped at exit.
#   scripts/brick-memory-slurm.sh [BUILD] [N] [B] [LIMIT_MIB] [SCRATCH]   (make bricks-slurm: build 2048 2 2048)
set -euo pipefail
build=${1:-build} n=${2:-2048} b=${3:-2} limit=${4:-2048} scratch=${5:-$build/bricks-slurm}
for value in "$n" "$b" "$limit"; do  # whole numbers before any arithmetic or YAML sees them
  [[ $value =~ ^[1-9][0-9]{0,5}$ ]] || { echo "brick-memory-slurm: N, B and LIMIT_MIB are whole numbers, got '$value'" >&2; exit 64; }
done
repo=$(cd "$(dirname "$0")/.." && pwd)
bin=$(cd "$build/bin" && pwd)
mkdir -p "$scratch" && cd "$scratch"
fail() { echo "brick-memory-slurm: $*" >&2; exit 1; }
volume=blobs_${n}x${n}x${n}_uint8.raw
if [ ! -f "$volume" ]; then
  echo "brick-memory-slurm: writing $volume ($((n * n * n / 1048576)) MiB)" >&2
  /usr/bin/python3 "$repo/scripts/blob-volume.py" "$n" "$volume"
fi
(( limit * 1048576 < n * n * n )) || fail "a brick job's limit of $limit MiB holds the whole volume: nothing to show"
cp "$repo/experiments/tf/blobs.yaml" tf.yaml
for what in whole bricked; do
  method="{method: riemann, step: 1}"
  [ "$what" = whole ] || method="{method: riemann, step: 1, bricks: [$b, $b, $b]}"
  cat > "$what.yaml" <<YAML
name: $what
title: A synthetic ${n}^3 volume, $what
paper: {paper: B, item: none, says: volumes larger than one job's memory}
scenes:
  blobs: {volume: $volume, convention: cell, tf: tf.yaml, size: [1920, 1080],
          camera: {eye: [$((n * 5 / 2)), $((n * 2)), $((-n * 3 / 2))], target: [$((n / 2)), $((n / 2)), $((n / 2))], up: [0, 1, 0], fov: 30}}
methods:
  render: $method
YAML
done
printf 'kinds:\n  brick: {mem: %dM}\n' "$limit" > profile.yaml

echo "brick-memory-slurm: the whole volume with the local executor" >&2
rm -rf local slurm cluster
"$bin/vri-run" --results local whole.yaml
source "$repo/tests/tools/lib/slurm_cluster.sh"
# The bricks of a large volume take minutes a pair on one core each: the cluster's watchdog waits an hour.
VRI_SLURM_TEST_LIMIT=${VRI_SLURM_TEST_LIMIT:-3600} start_slurm_cluster "$PWD/cluster" 10 2
echo "brick-memory-slurm: $((b * b * b)) bricks on the test cluster, each job given $limit MiB" >&2
VRI_SLURM_PROFILE=$PWD/profile.yaml "$bin/vri-run" --executor slurm --slurm-cpus 1 --slurm-poll 1 --results slurm bricked.yaml
/usr/bin/python3 - "$n" "$limit" "$b" <<'PY'
import json, sys
import numpy as np
import OpenImageIO as oiio
n, limit = int(sys.argv[1]), int(sys.argv[2])
mib = 1 << 20
manifest = json.load(open("slurm/bricked/manifest.json"))
steps, machine = manifest["steps"], manifest["machine"]
print(f"vri built from {manifest['build']['git_commit']}, run {manifest['steps'][0]['ran_utc']} on "
      f"{machine['cpu_model']}, {machine['logical_cores']} cores, {machine['memory_bytes'] / (1 << 30):.1f} GiB; "
      "the test cluster's two slurmd (one core each) on this machine.\n")
print(f"A {n}^3 uint8 volume ({n ** 3 / mib:.0f} MiB), each brick's Slurm job limited to {limit} MiB "
      "(jobacct_gather's OverMemoryKill):\n")
print("| step | job | node | volume bytes held (MiB) | layer image (MiB) | peak RSS (MiB) | peak / held | seconds |")
print("|---|---|---|--:|--:|--:|--:|--:|")
worst = 0.0
for s in steps:
    e = s["execution"]
    stats = [o["path"] for o in s["outputs"] if o["path"].endswith(".json")]
    held = image = 0.0
    if ".brick-" in s["id"] and stats:
        d = json.load(open(stats[0]))
        held = d["scene"]["volume_bytes"] / mib
        image = d["camera"]["width"] * d["camera"]["height"] * 16 / mib  # premultiplied colour and transmittance
        worst = max(worst, e["peak_rss_mib"] / (held + image))
    ratio = f"{e['peak_rss_mib'] / (held + image):.2f}" if held else ""
    print(f"| {s['id']} | {e['job_id']} | {e['node']} | {held:.0f} | {image:.0f} | {e['peak_rss_mib']:.0f} | {ratio} | "
          f"{s['wall_seconds']:.1f} |")
whole = json.load(open("local/whole/manifest.json"))["steps"][0]
print(f"| whole volume, local executor | | {whole['execution']['node']} | | | {whole['execution']['peak_rss_mib']:.0f} | | "
      f"{whole['wall_seconds']:.1f} |")
a = oiio.ImageBuf("local/whole/render.exr").get_pixels(oiio.FLOAT).astype(np.float64)
j = oiio.ImageBuf("slurm/bricked/render.exr").get_pixels(oiio.FLOAT).astype(np.float64)
joined = json.load(open("slurm/bricked/render.json"))
bound = joined["join"]["bound_max"]
diff = float(np.abs(a - j).max())
print(f"\nJoined against whole: largest difference {diff:.3g}, the join's bound {bound:.3g}, pixels that differ "
      f"{int(np.any(a != j, axis=2).sum())} of {a.shape[0] * a.shape[1]}; largest peak / held {worst:.2f}")
bricks = sum(".brick-" in s["id"] for s in steps)
sys.exit(0 if diff <= bound and bricks == int(sys.argv[3]) ** 3 and worst <= 1.3 else 1)
PY
