#!/usr/bin/env bash
# vri-tabulate end to end: paper B's threshold table, a timing matrix (median of three runs) and a
# speed-against-accuracy table with its Pareto fronts, exact Markdown and CSV, and failures that write nothing.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"

tabulate="$VRI_BIN/vri-tabulate"

grep -q "Example" <<<"$("$tabulate" --help)" || fail "--help shows no example"

# vri-diff JSON as it is written: channels R and A, thresholds 0.01 and 0.001, maximum errors (default 0.5),
# RMSE 0.01 and 0.02.
diff_json() {  # diff_json FILE R01 A01 R001 A001 [MAX_R MAX_A]
    cat > "$1" <<JSON
{"thresholds": [0.01, 0.001], "pixels": 100, "pixels_counted": "all", "channels": [
 {"name": "R", "max_abs": ${6:-0.5}, "rmse": 0.01, "above": [{"threshold": 0.01, "count": 1, "percent": $2}, {"threshold": 0.001, "count": 1, "percent": $4}]},
 {"name": "A", "max_abs": ${7:-0.5}, "rmse": 0.02, "above": [{"threshold": 0.01, "count": 1, "percent": $3}, {"threshold": 0.001, "count": 1, "percent": $5}]}]}
JSON
}
diff_json riemann.json 0.11389 12.766 12.4298 41.13684
diff_json coupled-0.01.json 0 0 9 9
diff_json coupled-0.001.json 9 9 0.0022 0.121
"$tabulate" --layout thresholds --title "Table I" --row "Riemann (h = 0.5)" riemann.json \
    --row Coupled coupled-0.01.json coupled-0.001.json -o t1.md --csv t1.csv
cat > expected.md <<'MD'
**Table I**

| Method | R > 0.01 | A > 0.01 | R > 0.001 | A > 0.001 |
|:--|--:|--:|--:|--:|
| Riemann (h = 0.5) | 0.114 | 12.8 | 12.4 | 41.1 |
| Coupled | 0 | 0 | 0.0022 | 0.121 |

Percentage of rays (all pixels, background included) whose absolute error exceeds the threshold, per channel, to 3 significant digits (0: no ray).
MD
diff -u expected.md t1.md || fail "threshold table Markdown"
printf 'Method,R > 0.01,A > 0.01,R > 0.001,A > 0.001\nRiemann (h = 0.5),0.114,12.8,12.4,41.1\nCoupled,0,0,0.0022,0.121\n' > expected.csv
diff -u expected.csv t1.csv || fail "threshold table CSV"

# Timings: the median of three runs per cell; a second column in frames per second.
for s in 3 1 2; do echo "{\"stats\": {\"wall_seconds\": $s}}" > "run$s.json"; done
"$tabulate" --layout matrix --value stats.wall_seconds --row-header "" --cell "Riemann h = 0.5" "CPU (s)" run3.json run1.json run2.json \
    --cell "Riemann h = 0.5" "GPU (fps)" run1.json run2.json run3.json \
    --column-value "GPU (fps)" 1/stats.wall_seconds --column-precision "GPU (fps)" 1 -o - --csv t3.csv > t3.md
cat > expected.md <<'MD'
|  | CPU (s) | GPU (fps) |
|:--|--:|--:|
| Riemann h = 0.5 | 2.00 | 0.5 |

Values: CPU (s): stats.wall_seconds; GPU (fps): 1/stats.wall_seconds.
Each cell is the median of 3 runs.
MD
diff -u expected.md t3.md || fail "matrix Markdown"
printf ',CPU (s),GPU (fps)\nRiemann h = 0.5,2.00,0.5\n' | diff -u - t3.csv || fail "matrix CSV"

# Speed against accuracy: per run its seconds (stats) and errors (diff) at 0.001; Simpson is faster and
# better in % than h = 0.5, but its infinite maximum error keeps it off the max front.
timing_json() {  # timing_json FILE SECONDS: 2e6 samples of Riemann in double on the CPU's scalar path
    echo "{\"timing\": {\"repeats\": 3, \"median_wall_seconds\": $2, \"wall_seconds\": [$2, $2, $2]}, \"options\": {\"method\": \"riemann\", \"precision\": \"double\"}," \
         "\"stats\": {\"backend\": \"cpu\", \"simd_target\": null, \"samples_evaluated\": 2e6}}" > "$1"
}
timing_json riemann-h1.json 0.1 && diff_json vs-riemann-h1.json 30 20 20 10 0.3 0.2
# The first run's machine record names the host under the table.
/usr/bin/python3 - <<'PY'
import json
run = json.load(open("riemann-h1.json"))
run["machine"] = {"cpu_model": "Test CPU", "usable_cores": 2, "cpu_simd_flags": ["sse4_2", "avx2"],
                  "simd_targets": ["AVX2", "SSE4", "SCALAR"]}
json.dump(run, open("riemann-h1.json", "w"))
PY
timing_json riemann-h0.5.json 0.4 && diff_json vs-riemann-h0.5.json 9 2 5 1 0.05 0.1
timing_json simpson.json 0.2 && diff_json vs-simpson.json 0 0 0 0.5 0.001 null
"$tabulate" --layout tradeoff --title "Speed against accuracy" --run riemann-h1 riemann-h1.json vs-riemann-h1.json \
    --run riemann-h0.5 riemann-h0.5.json vs-riemann-h0.5.json --run simpson-e0.001 simpson.json vs-simpson.json \
    -o speed.md --csv speed.csv
cat > expected.md <<'MD'
**Speed against accuracy**

| run | method | seconds | frames | spread % | ci low | ci high | Msamples/s | R > 0.001 | A > 0.001 | worst > 0.001 | max R | max A | max | rmse | pareto % | pareto max |
|:--|:--|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|
| riemann-h1 | riemann double | 0.1 | 3 | 0 | 0.1 | 0.1 | 20 | 20 | 10 | 20 | 0.3 | 0.2 | 0.3 | 0.02 | 1 | 1 |
| riemann-h0.5 | riemann double | 0.4 | 3 | 0 | 0.4 | 0.4 | 5 | 5 | 1 | 5 | 0.05 | 0.1 | 0.1 | 0.02 | 0 | 1 |
| simpson-e0.001 | riemann double | 0.2 | 3 | 0 | 0.2 | 0.2 | 10 | 0 | 0.5 | 0.5 | 0.001 | inf | inf | 0.02 | 1 | 0 |

method: the run's method and precision, SIMD where the float packets ran (and the SIMD target when a run asked for one below the best), vulkan on that backend. seconds: median wall time per frame (the run's timing.median_wall_seconds); frames: the timed frames it is the median of (after the run's warm-up frames); spread %: (slowest - fastest frame) / median, 0 for one frame, whose time is one sample.
ci low, ci high: the frames' order statistics that hold the median time with a known chance, whatever the times' distribution: the fastest and slowest of 3 frames (75 %) or of 5 (94 %); from 6 frames on, the narrowest such pair that holds it with at least 95 % (timing.median_ci).
Msamples/s: millions of samples evaluated per second (stats.samples_evaluated over seconds; - where the method counts none).
host: Test CPU, 2 usable cores; CPU flags: sse4_2 avx2; SIMD targets, best first: AVX2 SSE4 SCALAR.
R > t ... worst > t: % of rays (all pixels, background included) whose absolute error exceeds t (t = 0.001), to 3 significant digits (0: no ray), per channel and in the worst channel; max R ... max: the largest absolute error, per channel and over all; rmse: the largest root mean square error of a channel.
pareto % (pareto max): 1 on the Pareto front of seconds against worst > 0.001 (against max), where no other row is at least as fast and as accurate and better in one; an infinite error is never on it.
MD
diff -u expected.md speed.md || fail "tradeoff Markdown"
cat > expected.csv <<'CSV'
run,method,seconds,frames,spread %,ci low,ci high,Msamples/s,R > 0.001,A > 0.001,worst > 0.001,max R,max A,max,rmse,pareto %,pareto max
riemann-h1,riemann double,0.1,3,0,0.1,0.1,20,20,10,20,0.3,0.2,0.3,0.02,1,1
riemann-h0.5,riemann double,0.4,3,0,0.4,0.4,5,5,1,5,0.05,0.1,0.1,0.02,0,1
simpson-e0.001,riemann double,0.2,3,0,0.2,0.2,10,0,0.5,0.5,0.001,inf,inf,0.02,1,0
CSV
diff -u expected.csv speed.csv || fail "tradeoff CSV"
# Diffs with vri-diff's metrics add PSNR, SSIM and FLIP columns (empty for a diff without them, and a PSNR of
# equal images, null).
/usr/bin/python3 - <<'PY'
import json
d = json.load(open("vs-riemann-h1.json"))
d["metrics"] = {"all": {"psnr_db": 31.5, "ssim": 0.9876, "rel_mse": 0.1, "smape": 0.1}, "flip": {"ldr": {"mean": 0.0456}}}
json.dump(d, open("vs-riemann-h1-metrics.json", "w"))
PY
"$tabulate" --layout tradeoff --run riemann-h1 riemann-h1.json vs-riemann-h1-metrics.json \
    --run riemann-h0.5 riemann-h0.5.json vs-riemann-h0.5.json -o - --csv metrics.csv > /dev/null
[[ $(head -1 metrics.csv) == *",rmse,PSNR dB,SSIM,FLIP,pareto %,pareto max" ]] || fail "metric columns: $(head -1 metrics.csv)"
[[ $(sed -n 2p metrics.csv) == *",31.5,0.9876,0.0456,"* && $(sed -n 3p metrics.csv) == *",0.02,,,,"* ]] ||
  fail "metric cells: $(sed -n 2,3p metrics.csv)"
# Another threshold the diffs counted, other decimals and row heading.
"$tabulate" --layout tradeoff --threshold 0.01 --precision 1 --row-header Method \
    --run riemann-h1 riemann-h1.json vs-riemann-h1.json -o - | grep -q "^| Method | method | seconds | frames | spread % | ci low | ci high | Msamples/s | R > 0.01 | A > 0.01 | worst > 0.01 |" ||
    fail "tradeoff at 0.01"
# A run on a SIMD target forced below the best is a family of its own; the best's keeps its name.
for target in best AVX2; do
  forced=$([[ $target == best ]] || echo ", \"simd_target\": \"$target\"")
  echo "{\"timing\": {\"repeats\": 3, \"median_wall_seconds\": 0.1, \"wall_seconds\": [0.1, 0.1, 0.1]}, \"options\": {\"method\": \"riemann\", \"precision\": \"float\"$forced}," \
       "\"stats\": {\"backend\": \"cpu\", \"simd_target\": \"AVX3\", \"samples_evaluated\": 2e6}}" > "simd-$target.json"
done
"$tabulate" --layout tradeoff --run on simd-best.json vs-riemann-h1.json --run avx2 simd-AVX2.json vs-riemann-h1.json -o - > simd.md
grep -q "^| on | riemann float SIMD | " simd.md || fail "the best target's family: $(cat simd.md)"
grep -q "^| avx2 | riemann float SIMD AVX2 | " simd.md || fail "a forced target's family: $(cat simd.md)"

# Failures: one line, non-zero exit, nothing written.
rm -f t1.md t1.csv
expect_failure() {  # expect_failure TEXT ARGS...
    local text=$1 rc=0
    shift
    "$tabulate" "$@" >out.txt 2>err.txt || rc=$?
    [[ $rc -ne 0 ]] || fail "succeeded: $*"
    [[ $(wc -l <err.txt) -eq 1 ]] || fail "not one line: $(cat err.txt)"
    grep -q "$text" err.txt || fail "expected '$text': $(cat err.txt)"
    [[ ! -e t1.md && ! -e t1.csv ]] || fail "wrote output although it failed: $*"
}
expect_failure "missing.json: no such file" --layout thresholds --row R missing.json -o t1.md --csv t1.csv
expect_failure "no count above 0.5" --layout thresholds --thresholds 0.5 --row R riemann.json -o t1.md --csv t1.csv
expect_failure "'stats.nope' is no field of a render's stats" --layout matrix --value stats.nope --cell a b run1.json -o t1.md --csv t1.csv
expect_failure "value belongs to --layout matrix" --layout thresholds --row R riemann.json --value x -o t1.md
expect_failure "run belongs to --layout tradeoff" --layout thresholds --run R riemann-h1.json vs-riemann-h1.json -o t1.md
expect_failure "row belongs to --layout thresholds" --layout tradeoff --row R riemann.json -o t1.md
expect_failure "needs --run LABEL STATS DIFF" --layout tradeoff -o t1.md
expect_failure "vs-riemann-h1.json: no count above 0.005" --layout tradeoff --threshold 0.005 \
    --run R riemann-h1.json vs-riemann-h1.json -o t1.md --csv t1.csv
expect_failure "riemann.json: has no 'timing'" --layout tradeoff --run R riemann.json vs-riemann-h1.json -o t1.md
expect_failure "baseline 'riemann-h2': no row of that name" --layout tradeoff --baseline riemann-h2 \
    --run riemann-h1 riemann-h1.json vs-riemann-h1.json -o t1.md --csv t1.csv
expect_failure "channels: some not in" --layout tradeoff --channels some --run riemann-h1 riemann-h1.json vs-riemann-h1.json -o t1.md
expect_failure "baseline belongs to --layout tradeoff" --layout thresholds --baseline R --row R riemann.json -o t1.md
expect_failure "run: expected LABEL STATS DIFF, got 2 words" --layout tradeoff --run R riemann-h1.json -o t1.md
expect_failure "column-value: expected COLUMN EXPR, got 1 word" --layout matrix --value x --cell a b run1.json --column-value b -o t1.md
expect_failure "layout" --layout pie --row R riemann.json -o t1.md
echo "tabulate: all checks passed"
