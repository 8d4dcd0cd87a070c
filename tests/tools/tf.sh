#!/usr/bin/env bash
# vri-tf end to end: the table's shape, every breakpoint in it (both sides of a jump), the values
# between breakpoints, stdout output, paper B's tables drawn by their plot specs, and bad or missing
# transfer functions that write nothing.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"

tf="$VRI_BIN/vri-tf"

grep -q "Examples" <<<"$("$tf" --help)" || fail "--help shows no example"

# Breakpoints at 0.1 and 0.5 (on the grid of 11 samples), 0.35 (off it) and a jump at 0.73; a last
# point beyond 1 is not a row, but shapes the values up to s = 1.
cat > jump.yaml <<'YAML'
description: a ramp, a jump and a point past the end
points:
  - [0.1, 0, 0, 0, 0]
  - [0.35, 0.625, 0.3125, 0.15625, 1.25]
  - [0.5, 1, 0.5, 0.25, 2]
  - [0.73, 1, 0.5, 0.25, 2]
  - [0.73, 0, 0, 1, 0.5]
  - [1.5, 0, 0, 1, 1.5]
YAML
"$tf" jump.yaml --samples 11 -o jump.csv
head -1 jump.csv | grep -qx 's,r,g,b,tau,alpha_per_voxel' || fail "header: $(head -1 jump.csv)"
# 11 samples (0.1 and 0.5 shared with breakpoints), plus 0.35 and the two sides of 0.73: 14 rows.
[ "$(wc -l < jump.csv)" -eq 15 ] || fail "expected 14 rows, got $(($(wc -l < jump.csv) - 1))"
[ "$(awk -F, 'NR > 1 && NF != 6' jump.csv | wc -l)" -eq 0 ] || fail "a row without 6 fields"
awk -F, 'NR > 2 && $1 < prev { exit 1 } { prev = $1 }' jump.csv || fail "s is not sorted"
[ "$(grep -c '^0\.1,' jump.csv)" -eq 1 ] || fail "s = 0.1 should be one row (sample and breakpoint coincide)"
[ "$(grep -c '^0\.5,' jump.csv)" -eq 1 ] || fail "s = 0.5 should be one row (sample and breakpoint coincide)"
grep -q '^0\.35,0\.625,0\.3125,0\.15625,1\.25,' jump.csv || fail "breakpoint 0.35 missing"
grep -q '^0\.73,1,0\.5,0\.25,2,' jump.csv || fail "left side of the jump at 0.73 missing"
grep -q '^0\.73,0,0,1,0\.5,' jump.csv || fail "right side of the jump at 0.73 missing"
[ "$(grep -n '^0\.73,1,' jump.csv | cut -d: -f1)" -lt "$(grep -n '^0\.73,0,' jump.csv | cut -d: -f1)" ] ||
    fail "the jump's sides are out of order"
# Constant before the first point, linear between points (0.3 is 0.8 of the way from 0.1 to 0.35), and
# 1 - exp(-tau) beside tau.
grep -qx '0,0,0,0,0,0' jump.csv || fail "s = 0 should take the first point's values"
row_is() {  # row_is S R G B TAU: the row at s = S holds these values, and 1 - exp(-TAU), to 1e-12
    awk -F, -v s="$1" -v r="$2" -v g="$3" -v b="$4" -v tau="$5" '
        function near(x, y) { return (x - y)^2 < 1e-24 }
        $1 == s { found = 1; ok = near($2, r) && near($3, g) && near($4, b) && near($5, tau) && near($6, 1 - exp(-tau)) }
        END { exit !(found && ok) }' jump.csv || fail "row at s = $1: $(grep "^$1," jump.csv)"
}
row_is 0.3 0.5 0.25 0.125 1
row_is 1 0 0 1 "$(awk 'BEGIN { printf "%.17g", 0.5 + 0.27 / 0.77 }')"

# Defaults: 512 samples; stdout; the project's transfer functions all tabulate.
"$tf" "$VRI_SOURCE/experiments/tf/bonsai.yaml" -o - > bonsai.csv
[ "$(wc -l < bonsai.csv)" -ge 513 ] || fail "default of 512 samples"
for yaml in "$VRI_SOURCE"/experiments/tf/*.yaml; do
    "$tf" "$yaml" --samples 16 -o - > /dev/null || fail "$yaml does not tabulate"
done

# Paper B's transfer functions tabulate into the CSV their plot specs read (the script alone needs no gnuplot).
for name in bonsai bluntfin teapot engine; do
    "$tf" "$VRI_SOURCE/experiments/tf/paper-b-$name.yaml" -o "tf-$name.csv"
    "$VRI_BIN/vri-plot" "$VRI_SOURCE/experiments/plots/paper-b-tf-$name.yaml" --data-dir . -o "tf-$name.png" --script-only ||
        fail "plots/paper-b-tf-$name.yaml does not read tf-$name.csv"
done

# Bad input: one line naming the file, non-zero exit, nothing written.
bad() {  # bad PATTERN ARGS...
    local pattern=$1; shift
    rm -f out.csv
    if "$tf" "$@" -o out.csv 2> err.txt; then fail "accepted: $*"; fi
    [ "$(wc -l < err.txt)" -eq 1 ] || fail "not one line for '$*': $(cat err.txt)"
    grep -q -- "$pattern" err.txt || fail "'$*': expected '$pattern' in: $(cat err.txt)"
    [ ! -e out.csv ] || fail "'$*' wrote its output"
}
printf 'points:\n  - [0.5, 1, 1, 1, 1]\n  - [0.2, 1, 1, 1, 1]\n' > unsorted.yaml
bad "unsorted.yaml:3:.*sorted by s" unsorted.yaml
printf 'points:\n  - [0, 0, 0, 0, 0]\n  - [1, 1, 1, 1, -0.5]\n' > negative.yaml
bad "negative.yaml:3:.*negative extinction" negative.yaml
bad "missing.yaml" missing.yaml
bad "--samples" jump.yaml --samples 1

# --check: the documented example (experiments/README.md, "Transfer functions") reads as documented; a function
# that shows nothing, or covers only part of [0, 1], is said with warnings; a mistake is the usual one line.
sed -n '/^## Transfer functions/,/^## What lands/p' "$VRI_SOURCE/experiments/README.md" |
    sed -n '/^```yaml$/,/^```$/p' | sed '1d;$d' > documented.yaml
"$tf" --check documented.yaml > check.txt 2> check-err.txt || fail "the documented example: $(cat check-err.txt)"
[ "$(cat check.txt)" = "documented.yaml: 5 points, s from 0 to 1, emission color-times-extinction, largest tau 8, largest colour 1" ] ||
    fail "--check said: $(cat check.txt)"
[ ! -s check-err.txt ] || fail "warnings for the documented example: $(cat check-err.txt)"
printf 'points:\n  - [0.2, 1, 1, 1, 0]\n  - [0.5, 1, 1, 1, 0]\n' > invisible.yaml
"$tf" --check invisible.yaml > /dev/null 2> check-err.txt
grep -q "^vri-tf: warning: invisible.yaml: every tau is 0: the volume is invisible$" check-err.txt || fail "$(cat check-err.txt)"
grep -q "^vri-tf: warning: invisible.yaml: the points cover s from 0.2 to 0.5;" check-err.txt || fail "$(cat check-err.txt)"
if "$tf" --check unsorted.yaml > /dev/null 2> check-err.txt; then fail "--check accepted unsorted.yaml"; fi
[ "$(wc -l < check-err.txt)" -eq 1 ] && grep -q "unsorted.yaml" check-err.txt || fail "$(cat check-err.txt)"
echo "tf: ok"
