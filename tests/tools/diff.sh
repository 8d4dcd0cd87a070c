#!/usr/bin/env bash
# vri-diff end to end: statistics, outputs, and idiff's exit codes one up (0 pass, 2 warn, 3 fail,
# 4 different shapes; 1 a missing or unreadable file, as in every tool; 64 bad usage).
set -euo pipefail

command -v oiiotool >/dev/null || { echo "oiiotool not installed: skipping"; exit 77; }
command -v python3 >/dev/null || { echo "python3 not installed: skipping"; exit 77; }
diff_tool="$VRI_BIN/vri-diff"
mkdir -p "$VRI_SCRATCH"
cd "$VRI_SCRATCH"
rm -f ./*.exr ./*.json ./*.csv ./*.txt

oiiotool --pattern constant:color=0.5,0.2,0.1,1 8x8 4 -d float -o a.exr
oiiotool --pattern constant:color=0.5,0.2,0.1,1 8x8 4 -d float -o same.exr
# One pixel's R off by 0.25: 1 of 256 pixel-channels (0.390625 %).
oiiotool a.exr --pattern constant:color=0.25,0,0,0 1x1 4 -d float --origin +3+2 --add -o changed.exr
oiiotool --pattern constant:color=0.5,0.2,0.1,1 4x8 4 -d float -o small.exr
oiiotool --pattern constant:color=0.5,0.2,0.1 8x8 3 -d float -o rgb.exr

fail() { echo "FAILED: $*" >&2; exit 1; }

# Runs vri-diff with the given arguments; sets rc, leaves stdout in out.txt and stderr in err.txt.
run_diff() {
    rc=0
    "$diff_tool" "$@" >out.txt 2>err.txt || rc=$?
}

expect_rc() {
    [[ $rc -eq $1 ]] || { cat out.txt err.txt >&2; fail "$2: exit $rc, expected $1"; }
}

json_value() {  # json_value FILE PYTHON-EXPRESSION-ON-j
    /usr/bin/python3 -c "import json, sys; j = json.load(open(sys.argv[1])); print($2)" "$1"
}

# An image against itself: pass, and every statistic zero.
run_diff a.exr same.exr --json same.json
expect_rc 0 "identical images"
grep -q PASS out.txt || fail "identical images: no PASS in the summary"
[[ $(json_value same.json 'j["pixels_counted"]') == all ]] || fail "pixels_counted is not 'all'"
[[ $(json_value same.json 'max(c[k] for c in j["channels"] for k in ("max_abs", "mean_abs", "rmse"))') == 0.0 ]] ||
    fail "identical images: non-zero statistics"
[[ $(json_value same.json 'sum(a["count"] for c in j["channels"] for a in c["above"])') == 0 ]] ||
    fail "identical images: counts above thresholds"
[[ $(json_value same.json 'j["a"] + " " + j["b"]') == "a.exr same.exr" ]] || fail "input paths missing from JSON"

# A changed pixel: failure with the default --fail 1e-6, outputs written.
run_diff a.exr changed.exr --json changed.json --diff-image err.exr --histogram hist.csv
expect_rc 3 "changed image, default --fail"
grep -q FAIL out.txt || fail "changed image: no FAIL in the summary"
[[ $(json_value changed.json 'j["channels"][0]["max_at"]') == "[3, 2]" ]] || fail "max not located at (3,2)"
[[ $(json_value changed.json 'j["channels"][0]["above"][0]["count"]') == 1 ]] || fail "count above 0.01"
[[ $(json_value changed.json 'j["channels"][1]["max_abs"]') == 0.0 ]] || fail "G changed"
[[ -s err.exr ]] || fail "--diff-image not written"
[[ $(head -1 hist.csv) == "bin_lo,bin_hi,R,G,B,A" ]] || fail "histogram header: $(head -1 hist.csv)"
total=$(tail -n +2 hist.csv | awk -F, '{ s += $3 } END { print s }')
[[ $total -eq 64 ]] || fail "histogram R counts sum to $total, not 64"
# The difference image holds the error where it is.
run_diff err.exr a.exr --json - --threshold 0.3
[[ $(/usr/bin/python3 -c 'import json, sys; print(json.load(sys.stdin)["channels"][0]["max_abs"])' <out.txt) != 0.0 ]] ||
    fail "difference image is empty"
# --diff-scale multiplies it: twice the scale, twice the largest value.
run_diff a.exr changed.exr --diff-image err2.exr --diff-scale 2
run_diff err.exr err2.exr --json - --threshold 0.3
[[ $(/usr/bin/python3 -c 'import json, sys; c = json.load(sys.stdin)["channels"][0]; print(c["max_abs"] > 0)' <out.txt) == True ]] ||
    fail "--diff-scale 2 gives the same image"
run_diff a.exr changed.exr --diff-scale 2
expect_rc 64 "--diff-scale without --diff-image"
grep -q -- "--diff-image" err.txt || fail "--diff-scale without --diff-image: $(cat err.txt)"

# Tolerances: within --failpercent passes; --fail relaxed but --warn strict warns.
run_diff a.exr changed.exr --failpercent 0.5
expect_rc 2 "one pixel-channel in 256 with --failpercent 0.5 (still above --warn)"
run_diff a.exr changed.exr --failpercent 0.5 --warnpercent 0.5
expect_rc 0 "one pixel-channel in 256 with --failpercent 0.5 --warnpercent 0.5"
run_diff a.exr changed.exr --fail 0.3 --warn 0.1
expect_rc 2 "error 0.25 with --fail 0.3 --warn 0.1"
grep -q WARN out.txt || fail "no WARN in the summary"
run_diff a.exr changed.exr --fail 0.25 --warn 0.25
expect_rc 0 "an error equal to --fail is not above it"

# --json - prints JSON only.
run_diff a.exr changed.exr --json -
expect_rc 3 "--json -"
json_value out.txt 'j["verdict"]' | grep -qx fail || fail "--json - did not print the JSON verdict"
# --histogram - prints the CSV only: the summary would run into it.
run_diff a.exr changed.exr --histogram -
expect_rc 3 "--histogram -"
[[ $(head -1 out.txt) == "bin_lo,bin_hi,R,G,B,A" ]] && ! grep -q "FAIL" out.txt ||
  fail "--histogram - did not print the CSV alone: $(tail -1 out.txt)"

# Different sizes or channel counts: 4, one line on stderr.
run_diff a.exr small.exr
expect_rc 4 "different sizes"
[[ $(wc -l <err.txt) -eq 1 ]] || fail "different sizes: stderr is not one line"
run_diff a.exr rgb.exr
expect_rc 4 "different channel counts"

# Missing or unreadable file: 1, one line on stderr naming it.
run_diff a.exr missing.exr
expect_rc 1 "missing file"
[[ $(wc -l <err.txt) -eq 1 ]] || fail "missing file: stderr is not one line"
grep -q "missing.exr" err.txt || fail "missing file not named"
echo "not an image" >garbage.exr
run_diff garbage.exr a.exr
expect_rc 1 "unreadable file"
[[ $(wc -l <err.txt) -eq 1 ]] || fail "unreadable file: stderr is not one line"

# Pixel-channels or pixels: one pixel off in R and G is 2 of 256 pixel-channels (0.78125 %) but 1 of 64 pixels
# (1.5625 %, idiff's count, --per-pixel); every percentage says which.
oiiotool a.exr --pattern constant:color=0.25,0.25,0,0 1x1 4 -d float --origin +3+2 --add -o two.exr
run_diff a.exr two.exr --threshold 0.1 --json two.json
expect_rc 3 "two channels of one pixel"
grep -q "^all channels: % of pixel-channels (pixels x channels) *0.7812$" out.txt || fail "pixel-channel row: $(cat out.txt)"
grep -q "^any channel: % of pixels (as idiff counts, --per-pixel) *1.5625$" out.txt || fail "pixel row: $(cat out.txt)"
grep -q "^FAIL: 0.78125% of pixel-channels above 1e-06 (allowed 0%)$" out.txt || fail "verdict: $(cat out.txt)"
[[ $(json_value two.json 'j["fail"]["counted"]') == pixel-channels ]] || fail "the JSON does not say what it counted"
run_diff a.exr two.exr --per-pixel --failpercent 1.5 --json two-pixels.json
expect_rc 3 "--per-pixel: 1.5625 % of pixels is more than 1.5 %"
grep -q "^FAIL: 1.5625% of pixels above 1e-06 in some channel (allowed 1.5%)$" out.txt || fail "--per-pixel: $(cat out.txt)"
[[ $(json_value two-pixels.json 'j["fail"]["counted"], j["fail"]["count"]') == "pixels 1" ]] || fail "--per-pixel JSON"
run_diff a.exr two.exr --failpercent 1.5 --warnpercent 1.5
expect_rc 0 "pixel-channels: 0.78125 % is within 1.5 %"
if command -v idiff >/dev/null; then  # the same count as idiff's own
    idiff a.exr two.exr > idiff.txt 2>&1 || true
    grep -q "1 pixels (1.56%) over 1e-06" idiff.txt || fail "idiff counts otherwise: $(cat idiff.txt)"
fi

# Help: exit 0, exit codes and examples.
run_diff --help
expect_rc 0 "--help"
grep -q "Example" out.txt || fail "--help has no examples"
grep -q "4 images differ" out.txt || fail "--help does not state the exit codes"

echo "diff.sh: all checks passed"
