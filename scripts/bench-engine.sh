#!/usr/bin/env bash
# Interleaved timings of the CPU engines on paper B's Bonsai scene (experiments/paper-b-cpu.yaml: 800x600,
# its camera and TF): each configuration renders --warm-up 1 --repeat 1 per round, ROUNDS rounds in turn,
# so that a load on the machine falls on every configuration alike. Prints each configuration's median
# seconds, its ratio to scalar double Riemann h = 0.5 of the same build in the same run, and its
# evaluated samples per second (millions; frame time only, the empty-space grid's setup is not in it).
#   scripts/bench-engine.sh [BUILD_DIRS] [ROUNDS] [THREADS]      (VRI_DATA_DIR: the volumes)
# BUILD_DIRS: one build folder, or several separated by commas (before,after), timed in turn;
# BENCH_CONFIGS: 'name|options;name|options...' instead of the default set (the first is the baseline).
set -euo pipefail
IFS=, read -ra builds <<< "${1:-build}"
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
    "riemann-double-h0.5-auto|--step 0.5 --early-termination auto"
    "riemann-float-simd-h0.1-auto|--step 0.1 --precision float --early-termination auto"
)
[[ -n ${BENCH_CONFIGS:-} ]] && mapfile -t configs < <(printf '%s\n' "$BENCH_CONFIGS" | tr ';' '\n')
for ((r = 0; r < rounds; ++r)); do
    for c in "${configs[@]}"; do
        name=${c%%|*}
        read -ra extra <<< "${c#*|}"
        for ((b = 0; b < ${#builds[@]}; ++b)); do
            "${builds[b]}/bin/vri-render" "${scene[@]}" "${extra[@]}" --warm-up 1 -o "$work/$name.$b.exr" \
                --stats "$work/$name.$b.$r.json" 2> "$work/stderr" || true  # an option the build lacks: no row
        done
    done
done
python3 - "$work" "$rounds" "${#builds[@]}" "${builds[@]}" "${configs[@]}" <<'PY'
import json, os, statistics, sys
work, rounds, nb = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
builds, configs = sys.argv[4:4 + nb], [c.split('|')[0] for c in sys.argv[4 + nb:]]
def row(name, b):
    files = [f"{work}/{name}.{b}.{r}.json" for r in range(rounds)]
    if not all(os.path.exists(f) for f in files): return None
    runs = [json.load(open(f)) for f in files]
    bound = runs[0]["stats"].get("error_bound", {}).get("max")
    left = runs[0]["stats"].get("termination_left_out_max")
    seconds = statistics.median(j["timing"]["median_wall_seconds"] for j in runs)
    return seconds, max(bound) if bound else left, runs[0]["stats"].get("samples_evaluated", 0) / seconds / 1e6
print(f"{'configuration':28s}" + "".join(f" {b[-16:]:>16s} s  ratio  bound  M/s  " for b in builds))
base = [row(configs[0], b) for b in range(nb)]
for name in configs:
    line = f"{name:28s}"
    for b in range(nb):
        r = row(name, b)
        line += f" {'':>18s}      {'':>6s}     " if r is None or base[b] is None else \
                f" {r[0]:18.3f} {r[0] / base[b][0]:6.3f}  {'' if r[1] is None else f'{r[1]:.2g}':6s} {r[2]:4.0f}"
    print(line)
PY
