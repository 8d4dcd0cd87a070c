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

# No two tic labels of a log axis closer than 4 % of its length (libvri's kMinTicSpacing), read from the
# script: every explicit tic list against the axis's range, in log space. Prints how many lists held a 0
# (a band for values <= 0) and how many were checked.
check_tic_spacing() {
    awk -v file="$1" '
        /^    # panel/ { delete tics; delete logscale }
        /^    set logscale [xy]$/ { logscale[$3] = 1 }
        /^    set [xy]tics \(/ {
            axis = substr($2, 1, 1); list = $0
            sub(/^[^(]*\(/, "", list); sub(/\)$/, "", list)
            tics[axis] = list
        }
        /^    set [xy]range \[/ {
            axis = substr($2, 1, 1)
            if (!logscale[axis] || !(axis in tics)) next
            range = $3; gsub(/[\[\]]/, "", range); split(range, ends, ":")
            lo = log(ends[1]); len = log(ends[2]) - lo
            n = split(tics[axis], entries, ", ")
            for (i = 1; i <= n; i++) { k = split(entries[i], words, " "); at[i] = (log(words[k]) - lo) / len }
            for (i = 1; i <= n; i++) for (j = i + 1; j <= n; j++) {
                d = at[j] - at[i]; if (d < 0) d = -d
                if (d < 0.04 - 1e-9) { printf "%s: %s tics %s and %s only %.3f of the axis apart\n", file, axis, entries[i], entries[j], d; bad = 1 }
            }
            checked++; if (tics[axis] ~ /^.0. /) zeros++
            delete tics[axis]
        }
        END { print zeros + 0, checked + 0; exit bad }' "$2"
}

# A histogram of counts with empty bins on a log axis (as paper B Fig. 4): the empty bins on a band
# labelled 0 below a break, never a 0 tic beside the real 1 or 0.1.
printf 'bin_hi,R\n1e-6,800\n1e-5,3000\n1e-4,20000\n1e-3,12000\n1e-2,3\n0.03,1\n0.1,0\n1,0\n' > data/counts.csv
cat > figs/counts.yaml <<'YAML'
x: {label: "|error|", log: true, range: [1e-6, 1]}
y: {label: rays, log: true}
series:
  - {file: ../data/counts.csv, x: bin_hi, y: R, style: linespoints}
YAML
"$plot" figs/counts.yaml -o out/counts.png --script-only
grep -q "^    set ylabel 'rays (0 on the grey band below the break)'$" out/counts.gp || fail "the axis does not say where 0 is"
grep -q "^    set ytics ('0' [0-9.e+-]*, 1, 10, 100, 1000, 10000)$" out/counts.gp || fail "tics: $(grep ytics out/counts.gp)"
grep -q "^    set object rect from graph 0, graph 0 to graph 1, graph 0.05 fc rgb '#e0e0e0'" out/counts.gp || fail "no band"
! grep -q "tics add" out/counts.gp || fail "a tic added by hand"
[[ $(check_tic_spacing counts.yaml out/counts.gp) == "1 1" ]] || fail "counts.yaml's tics"
# Every committed figure spec with its committed data (experiments/E.yaml's figures, from results/E/):
# the tic labels of its log axes keep apart, Paper B's Figs. 4 and 5 among them, whose empty bins are 0.
zeros=0
for experiment in "$VRI_SOURCE"/experiments/*.yaml; do
    name=$(basename "$experiment" .yaml)
    [ -d "$VRI_SOURCE/results/$name" ] || continue
    for spec in $(grep -oE 'spec: plots/[A-Za-z0-9_.-]+\.yaml' "$experiment" | sed 's/^spec: //'); do
        "$plot" "$VRI_SOURCE/experiments/$spec" --data-dir "$VRI_SOURCE/results/$name" -o "committed/$name/$(basename "$spec" .yaml).png" \
            --script-only 2>/dev/null || continue  # data not (yet) in results/
        counts=$(check_tic_spacing "$spec" "committed/$name/$(basename "$spec" .yaml).gp") || fail "$counts"
        zeros=$((zeros + ${counts%% *}))
    done
done
[[ $zeros -ge 8 ]] || fail "the committed specs have $zeros axes with a band for 0, Figs. 4 and 5 alone 8"

# A convergence study's chart: reference slopes, a tic at every step h, the key below the panel.
printf 'h,error\n0.2,0.1\n0.1,0.03\n0.05,0.01\n0.025,3e-3\n0.0125,1e-3\n' > data/orders.csv
cat > figs/orders.yaml <<'YAML'
size: [600, 600]
x: {label: h, log: true, ticks: data}
y: {label: error, log: true}
key: below
reference_slopes: [1, 2, 4]
series:
  - {file: ../data/orders.csv, x: h, y: error, style: linespoints, label: riemann}
YAML
"$plot" figs/orders.yaml -o out/orders.png --script-only
grep -q "^    set xtics (0.0125, 0.025, 0.05, 0.1, 0.2)$" out/orders.gp || fail "not every step ticked"
grep -q "^    set key below vertical maxcols 1$" out/orders.gp || fail "key not below"
for order in 1 2 4; do
    grep -q "^    set label 'order $order' at " out/orders.gp || fail "no order $order line"
done
[[ $(grep -c " nohead dt 2 lw 1 lc rgb 'gray50' back$" out/orders.gp) -eq 3 ]] || fail "not three reference lines"
rc=0
sed 's/reference_slopes: \[1, 2, 4\]/reference_slopes: [1, 0]/' figs/orders.yaml > figs/bad-slopes.yaml
"$plot" figs/bad-slopes.yaml -o bad/orders.png 2>err.txt || rc=$?
[[ $rc -ne 0 && $(wc -l <err.txt) -eq 1 ]] && grep -q "figs/bad-slopes.yaml:5:23: reference_slopes\[1\] must be a positive number" err.txt ||
    fail "a reference slope of 0: $(cat err.txt)"

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
for figure in counts orders; do
    "$plot" figs/$figure.yaml -o out/$figure.png 2>err.txt
    [[ ! -s err.txt ]] || fail "gnuplot warned on $figure: $(cat err.txt)"
    [[ $(head -c 8 out/$figure.png | od -An -tx1 | tr -d ' ') == 89504e470d0a1a0a ]] || fail "$figure.png is not a PNG"
done
# gnuplot's log of a vri-plot killed with -9 (issue 48, class 10): the next run removes it, a file of a
# process that is gone, and leaves a live process's alone.
sh -c 'exit 0' & gone=$!; wait "$gone"
: > "out/.fig.tmp.$gone.log"
sleep 1000 & live=$!
: > "out/.fig.tmp.$live.log"
"$plot" figs/fig.yaml -o out/fig.png 2> err.txt || fail "the rerun after a killed one: $(cat err.txt)"
[ ! -e "out/.fig.tmp.$gone.log" ] || fail "the log of a process that is gone was left"
[ -e "out/.fig.tmp.$live.log" ] || fail "the log of a live process was removed"
kill "$live"; rm -f "out/.fig.tmp.$live.log"
echo "plot: all checks passed"
