#!/usr/bin/env bash
# vri-rays2d end to end: paper A's fan (120 rays, 101 of them hit the square), the closed form
# against each placement, the error table, the Fig. 1 diagram and Fig. 3 field; bad arguments write nothing.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"

rays2d="$VRI_BIN/vri-rays2d"

grep -q "Examples" <<<"$("$rays2d" --help)" || fail "--help shows no example"

"$rays2d" -o rays.csv --errors errors.md --errors-csv errors.csv --convergence conv.csv \
    --diagram fig1.csv --field-image field.csv --field-resolution 11
head -1 rays.csv | grep -q '^ray,angle_deg,length,closed_form,eye_r1,eye_r4,eye_r16,' || fail "rays.csv header: $(head -1 rays.csv)"
[ "$(wc -l < rays.csv)" -eq 121 ] || fail "rays.csv should hold 120 rays"
hits=$(awk -F, 'NR > 1 && $3 > 0' rays.csv | wc -l)
[ "$hits" -eq 101 ] || fail "expected 101 rays through the square, got $hits"
# Ray 105: the closed form is positive, Entry Exit Align has no sample at rate 1, the corner variant one.
col() { head -1 rays.csv | tr , '\n' | grep -nx "$1" | cut -d: -f1; }
row105=$(awk -F, '$1 == 105' rays.csv)
closed=$(echo "$row105" | cut -d, -f"$(col closed_form)")
ee=$(echo "$row105" | cut -d, -f"$(col n_entry-exit_r1)")
eec=$(echo "$row105" | cut -d, -f"$(col n_entry-exit-corner_r1)")
awk -v c="$closed" 'BEGIN { exit !(c > 0.05) }' || fail "ray 105 closed form $closed"
[ "$ee" = 0 ] && [ "$eec" = 1 ] || fail "ray 105: entry-exit $ee samples, corner $eec (expected 0 and 1)"
grep -q '^| entry-exit-corner, 16 |' errors.md || fail "errors.md lacks the corner row"
[ "$(wc -l < errors.csv)" -eq 13 ] || fail "errors.csv: 12 rows expected"
head -1 conv.csv | grep -qx 'rate,eye_max,eye_mean,entry_max,entry_mean,entry-exit_max,entry-exit_mean,entry-exit-corner_max,entry-exit-corner_mean' \
    || fail "conv.csv header"
grep -q '^entry-exit,missed,' fig1.csv || fail "the diagram shows no missed stretch for Entry Exit Align"
[ "$(wc -l < field.csv)" -eq 122 ] || fail "field.csv: 11 x 11 points expected"

# The closed form does not depend on the placements or rates asked for, and the CSV is deterministic.
"$rays2d" --placements entry --rates 2 -o again.csv
cmp <(cut -d, -f1-4 rays.csv) <(cut -d, -f1-4 again.csv) || fail "closed form changed with the placements"
"$rays2d" -o rays2.csv --errors errors2.md --errors-csv errors2.csv --convergence conv2.csv
cmp rays.csv rays2.csv || fail "two runs differ"

# Cell-centred data: a different closed form on the same rays.
"$rays2d" --convention cell -o cell.csv
cmp -s <(cut -d, -f4 rays.csv) <(cut -d, -f4 cell.csv) && fail "cell and node closed forms coincide"

# Bad arguments: one line naming the option, non-zero exit, nothing written.
bad() {  # bad PATTERN ARGS...
    local pattern=$1; shift
    rm -f out.csv
    if "$rays2d" "$@" -o out.csv 2> err.txt; then fail "accepted: $*"; fi
    [ "$(wc -l < err.txt)" -eq 1 ] || fail "not one line for '$*': $(cat err.txt)"
    grep -q -- "$pattern" err.txt || fail "'$*': expected '$pattern' in: $(cat err.txt)"
    [ ! -e out.csv ] || fail "'$*' wrote its output"
}
bad "--rates" --rates 1,0
bad "--rates" --rates 1,,4
bad "--placements" --placements eye,middle
bad "--convention" --convention corner
bad "--eye" --eye 1,2,3
bad "--diagram-rays" --diagram fig.csv --diagram-rays 120
bad "at least 2x2" --grid 1
bad "field of view" --fov 180
if "$rays2d" 2> err.txt; then fail "ran with nothing to write"; fi
grep -q "nothing to write" err.txt || fail "no output asked: $(cat err.txt)"
echo "rays2d: ok"
