#!/usr/bin/env bash
# vri-tabulate end to end: paper B's threshold table and a timing matrix (median of three runs),
# exact Markdown and CSV, and failures that write nothing.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"

tabulate="$VRI_BIN/vri-tabulate"

"$tabulate" --help | grep -q "Example" || fail "--help shows no example"

# vri-diff JSON as it is written: channels R and A, thresholds 0.01 and 0.001.
diff_json() {  # diff_json FILE R01 A01 R001 A001
    cat > "$1" <<JSON
{"thresholds": [0.01, 0.001], "pixels": 100, "pixels_counted": "all", "channels": [
 {"name": "R", "max_abs": 0.5, "above": [{"threshold": 0.01, "count": 1, "percent": $2}, {"threshold": 0.001, "count": 1, "percent": $4}]},
 {"name": "A", "max_abs": 0.5, "above": [{"threshold": 0.01, "count": 1, "percent": $3}, {"threshold": 0.001, "count": 1, "percent": $5}]}]}
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
| Riemann (h = 0.5) | 0.1139 | 12.7660 | 12.4298 | 41.1368 |
| Coupled | 0.0000 | 0.0000 | 0.0022 | 0.1210 |

Percentage of rays (all pixels, background included) whose absolute error exceeds the threshold, per channel.
MD
diff -u expected.md t1.md || fail "threshold table Markdown"
printf 'Method,R > 0.01,A > 0.01,R > 0.001,A > 0.001\nRiemann (h = 0.5),0.1139,12.7660,12.4298,41.1368\nCoupled,0.0000,0.0000,0.0022,0.1210\n' > expected.csv
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
expect_failure "has no 'stats.nope'" --layout matrix --value stats.nope --cell a b run1.json -o t1.md --csv t1.csv
expect_failure "belong to --layout matrix" --layout thresholds --row R riemann.json --value x -o t1.md
expect_failure "layout" --layout pie --row R riemann.json -o t1.md
echo "tabulate: all checks passed"
