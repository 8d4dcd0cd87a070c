#!/usr/bin/env bash
# The README's quick tour, literally: its commands taken from README.md and run under `set -e` without a
# terminal, from a folder laid out as the repository root (build/ and experiments/), on the volumes of
# $VRI_DATA_DIR; every command must exit 0 and write what it names.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
data=${VRI_DATA_DIR:-$VRI_SOURCE/../shared/data/volumes}
for volume in boron.dat bonsai_256x256x256_uint8.raw; do
    [ -e "$data/$volume" ] || { echo "no $volume in $data (set VRI_DATA_DIR): skipping"; exit 77; }
done
export VRI_DATA_DIR=$data
ln -s "$VRI_BUILD" build
ln -s "$VRI_SOURCE/experiments" experiments

# The indented block after "A quick tour, from the repository root:", its continuation lines kept.
awk '/A quick tour, from the repository root:$/ {on = 1; next} on && /^$/ && started {exit}
     on && /^    / {started = 1; print substr($0, 5)}' "$VRI_SOURCE/README.md" > tour.sh
[ "$(grep -c 'build/bin/' tour.sh)" -ge 5 ] || fail "the tour was not found in README.md: $(cat tour.sh)"
bash -e tour.sh > tour.out 2> tour.err || fail "the tour stopped (exit $?): $(tail -n 5 tour.err)"

test -s bonsai.exr && test -s bonsai.png && test -s bonsai.json && test -s bonsai-h0.1.exr || fail "outputs missing"
grep -q '"verdict": "pass"' tour.out || fail "vri-diff's verdict: $(grep verdict tour.out)"
grep -q 'vri-render .*-o ' tour.out || fail "vri-run --dry-run printed no command"
echo "tour: $(grep -c 'build/bin/' tour.sh) commands ran under set -e"
