#!/usr/bin/env bash
# vri-plot end to end: a figure (PNG, SVG and the gnuplot script that redraws it by hand), and a
# malformed spec that fails with one file:line:col line and writes nothing.
set -euo pipefail

plot="$VRI_BIN/vri-plot"
mkdir -p "$VRI_SCRATCH"
cd "$VRI_SCRATCH"
rm -rf ./* ./.[!.]*

fail() { echo "FAIL: $*" >&2; exit 1; }

"$plot" --help | grep -q "Example" || fail "--help shows no example"

mkdir -p data figs
printf 'method,seconds,error\nriemann,2,0.1\ncoupled,1,0.2\nslow,3,0.3\n' > data/speed.csv
printf 'bin_lo,bin_hi,R,G,B,A\n0,0,5,5,5,5\n0,1e-3,1,2,3,4\n1e-3,1e-2,3,0,1,1\n1e-2,1,1,3,1,0\n1,inf,0,0,0,0\n' > data/hist.csv
cat > figs/fig.yaml <<'YAML'
title: speed and accuracy
size: [900, 400]
panels:
  - title: time against error
    x: {label: seconds per frame, log: true}
    y: {label: error, log: true}
    pareto: true
    series:
      - {file: ../data/speed.csv, x: seconds, y: error, style: points, label: methods}
  - title: error histogram
    x: {label: error, log: true}
    y: rays
    series:
      - {file: ../data/hist.csv, y: R, style: histogram, label: R}
      - {file: ../data/hist.csv, y: A, style: histogram, label: A}
YAML

# The script alone needs no gnuplot.
"$plot" figs/fig.yaml -o out/fig.png --script-only
[[ -s out/fig.gp && ! -e out/fig.png ]] || fail "--script-only"
grep -q "'../data/speed.csv' skip 1 using 2:3" out/fig.gp || fail "data path not relative to the script"

# A malformed spec: one line naming file, line and column; non-zero exit; nothing written.
sed 's/y: error, style/y: erorr, style/' figs/fig.yaml > figs/bad.yaml
rc=0
"$plot" figs/bad.yaml -o bad/fig.png >out.txt 2>err.txt || rc=$?
[[ $rc -ne 0 ]] || fail "a malformed spec passed"
[[ $(wc -l <err.txt) -eq 1 ]] || fail "not one line: $(cat err.txt)"
grep -q "^vri-plot: error: figs/bad.yaml:9:50: column 'erorr' is not in" err.txt || fail "message: $(cat err.txt)"
[[ ! -e bad ]] || fail "a malformed spec wrote output"

if ! command -v gnuplot >/dev/null; then
    echo "gnuplot not installed: skipping the drawing"
    exit 77
fi
rm -rf out
"$plot" figs/fig.yaml -o out/fig.png
[[ $(head -c 8 out/fig.png | od -An -tx1 | tr -d ' ') == 89504e470d0a1a0a ]] || fail "fig.png is not a PNG"
grep -q "<svg" out/fig.svg || fail "fig.svg is not SVG"
[[ $(ls -A out | tr '\n' ' ') == "fig.gp fig.png fig.svg " ]] || fail "left over: $(ls -A out)"
# Redrawn by hand from another directory, the script writes the same figure beside itself.
rm out/fig.png out/fig.svg
(cd / && gnuplot "$VRI_SCRATCH/out/fig.gp")
[[ -s out/fig.png && -s out/fig.svg ]] || fail "gnuplot fig.gp did not redraw the figure"
echo "plot: all checks passed"
