#!/usr/bin/env bash
# Interleaved timings of the CPU engines on paper B's Bonsai scene (experiments/paper-b-cpu.yaml: 800x600,
# its camera and TF): each configuration renders --warm-up 1 --repeat 1 per round, ROUNDS rounds in turn,
# so that a load on the machine falls on every configuration alike. Prints each configuration's median
# seconds and its ratio to scalar double Riemann h = 0.5 of the same run.
#   scripts/bench-engine.sh [BUILD_DIR] [ROUNDS] [THREADS]      (VRI_DATA_DIR: the volumes)
set -euo pipefail
build=${1:-build}
rounds=${2:-5}
threads=${3:-2}
data=${VRI_DATA_DIR:-../shared/data/volumes}
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf -- "$work"' EXIT
scene=(--volume "$data/bonsai_256x256x256_uint8.raw" --tf "$here/experiments/tf/paper-b-bonsai.yaml"
       --size 800x600 --eye 128,190,-340 --target 128,115,128 --up 0,1,0 --fov 38 --threads "$threads" -q)
configs=(
    "riemann-double-h0.5|--step 0.5"
    "riemann-float-simd-h0.5|--step 0.5 --precision float"
    "riemann-double-h0.1|--step 0.1"
    "riemann-float-simd-h0.1|--step 0.1 --precision float"
    "exact-1e-7|--method exact --tolerance 1e-7"
    "exact-1e-6|--method exact --tolerance 1e-6"
)
[[ -n ${BENCH_CONFIGS:-} ]] && mapfile -t configs < <(printf '%s\n' "$BENCH_CONFIGS" | tr ';' '\n')
for ((r = 0; r < rounds; ++r)); do
    for c in "${configs[@]}"; do
        name=${c%%|*}
        read -ra extra <<< "${c#*|}"
        "$build/bin/vri-render" "${scene[@]}" "${extra[@]}" --warm-up 1 -o "$work/$name.exr" --stats "$work/$name.$r.json"
    done
done
python3 - "$work" "$rounds" "${configs[@]}" <<'PY'
import json, statistics, sys
work, rounds, configs = sys.argv[1], int(sys.argv[2]), sys.argv[3:]
med = {}
for c in configs:
    name = c.split('|')[0]
    runs = [json.load(open(f"{work}/{name}.{r}.json")) for r in range(rounds)]
    med[name] = statistics.median(j["timing"]["median_wall_seconds"] for j in runs)
    extra = runs[0]["stats"].get("error_bound", {}).get("max")
    med[name, "bound"] = max(extra) if extra else None
base = med[configs[0].split('|')[0]]
print(f"{'configuration':28s} {'median s':>9s} {'ratio':>7s}  bound")
for c in configs:
    name = c.split('|')[0]
    b = med[name, "bound"]
    print(f"{name:28s} {med[name]:9.3f} {med[name] / base:7.3f}  {'' if b is None else f'{b:.3g}'}")
PY
