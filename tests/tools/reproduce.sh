#!/usr/bin/env bash
# The reproducibility check: every experiment with a reproduce: block is run at its quick size and
# its chosen numbers are compared with results/<experiment>/reproduce.json within the tolerances
# the file states; and a CPU render is bitwise the same run to run and on 1 or 2 threads.
set -euo pipefail
bin=${VRI_BIN:?} src=${VRI_SOURCE:?} dir=${VRI_SCRATCH:?}
rm -rf "$dir" && mkdir -p "$dir" && cd "$dir"
# The volumes, as the Makefile finds them when ctest runs without it (a relative default would start here).
export VRI_DATA_DIR=${VRI_DATA_DIR:-$src/../shared/data/volumes}

experiments=$(grep -l '^reproduce:' "$src"/experiments/*.yaml || true)
[ -n "$experiments" ] || { echo "no experiment has a reproduce: block"; exit 77; }
# shellcheck disable=SC2086  # one word per file
"$bin/vri-run" --quick --check --results quick --committed "$src/results" $experiments

# Bitwise determinism: a render of the quick run, done again by its own command on 1 and on 2
# threads (outputs redirected), equals the quick run's image.
line=$("$bin/vri-run" --quick --dry-run --results quick "$src/experiments/paper-a-fig4.yaml" | grep -- "-o quick/paper-a-fig4/riemann-eye.exr")
eval "words=($line)"
render=()
for ((i = 0; i < ${#words[@]}; i++)); do
  case ${words[i]} in -o|--png|--stats) i=$((i + 1));; *) render+=("${words[i]}");; esac
done
"${render[@]}" --threads 1 -o t1.exr
"${render[@]}" --threads 2 -o t2.exr
"$bin/vri-diff" quick/paper-a-fig4/riemann-eye.exr t1.exr --fail 0 > /dev/null
"$bin/vri-diff" quick/paper-a-fig4/riemann-eye.exr t2.exr --fail 0 > /dev/null
echo "reproduce: all checks passed"
