#!/usr/bin/env bash
# vri-plot end to end: a figure (PNG, SVG and the gnuplot script that redraws it by hand), a
# heatmap and a diagram of segments, a spec drawn from another data folder (--data-dir), and a
# malformed spec that fails with one file:line:col line and writes nothing.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"

plot="$VRI_BIN/vri-plot"

grep -q "Example" <<<"$("$plot" --help)" || fail "--help shows no example"
# The examples name a spec and a results folder of the repository that exist.
help=$("$plot" --help)
for path in $(grep -oE '(experiments|results)/[A-Za-z0-9_./-]+' <<<"$help"); do
    case $path in
        *.png) path=$(dirname "$path") ;;  # an output: its folder must exist
    esac
    [ -e "$VRI_SOURCE/$path" ] || fail "--help names $path, which is not in the repository"
done

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

# A heatmap (its grid written column by column, not in gnuplot's scan order) and a diagram of
# segments, both with data paths relative to --data-dir rather than to the spec.
mkdir -p results/a
awk 'BEGIN { print "u,v,f"; for (i = 0; i <= 20; i++) for (j = 0; j <= 20; j++)
             printf "%g,%g,%g\n", i / 20, j / 20, sin(3.14159265 * i / 20) * j / 20 }' > results/a/f.csv
# Per sample: the stretch of the ray it stands for (t0 to t1) on its placement's row, from lo to hi.
awk 'BEGIN { print "t0,t1,placement,t,lo,hi"
             for (i = 0; i < 4; i++) printf "%g,%g,1,%g,0.9,1.1\n", i / 4, (i + 1) / 4, (i + 0.5) / 4
             for (i = 0; i <= 4; i++) printf "%g,%g,2,%g,1.9,2.1\n", i ? (i - 0.5) / 4 : 0, i < 4 ? (i + 0.5) / 4 : 1, i / 4 }' \
    > results/a/samples.csv
cat > figs/heat.yaml <<'YAML'
size: [900, 400]
panels:
  - title: f(u, v) = sin(pi u) v
    aspect: equal
    x: u
    y: v
    colorbar: {label: f, min: 0, max: 1, palette: viridis}
    labels:
      - {x: 0.05, y: 0.9, text: top}
    series:
      - {file: f.csv, x: u, y: v, z: f, style: heatmap}
  - title: where samples go along a ray
    x: {label: t, range: [-0.05, 1.05]}
    y: {label: placement, range: [0.5, 2.8]}
    key: off
    labels:
      - {x: 0, y: 1.25, text: midpoints}
      - {x: 0, y: 2.25, text: ends}
    series:
      - {file: samples.csv, x: t0, y: placement, x2: t1, y2: placement, style: segments, width: 3, color: "#1f77b4"}
      - {file: samples.csv, x: t0, y: lo, x2: t0, y2: hi, style: segments, width: 1, color: "#000000"}
      - {file: samples.csv, x: t, y: placement, style: points, size: 1.5, point: square, color: "#d62728"}
YAML
"$plot" figs/heat.yaml --data-dir results/a -o results/a/heat.png --script-only
grep -q "with image notitle" results/a/heat.gp || fail "no image in the heatmap's script"
grep -q "with vectors nohead lw 3" results/a/heat.gp || fail "no segments in the script"
grep -q "^'samples.csv' skip 1\|plot 'samples.csv' skip 1" results/a/heat.gp || fail "data path not from --data-dir"
rc=0
"$plot" figs/heat.yaml -o heat/heat.png --script-only 2>err.txt || rc=$?
[[ $rc -ne 0 ]] && grep -q "figs/heat.yaml:11:.*data file figs/f.csv does not exist" err.txt ||
    fail "without --data-dir: $(cat err.txt)"
rc=0
"$plot" figs/heat.yaml --data-dir results/none -o heat/heat.png 2>err.txt || rc=$?
[[ $rc -ne 0 && ! -e heat ]] || fail "a missing --data-dir passed"

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
"$plot" figs/heat.yaml --data-dir results/a -o results/a/heat.png 2>err.txt
[[ ! -s err.txt ]] || fail "gnuplot warned: $(cat err.txt)"
[[ $(head -c 8 results/a/heat.png | od -An -tx1 | tr -d ' ') == 89504e470d0a1a0a ]] || fail "heat.png is not a PNG"
grep -q "<image" results/a/heat.svg || fail "heat.svg has no image"
echo "plot: all checks passed"
