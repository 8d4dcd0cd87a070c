#!/usr/bin/env bash
# A new study, as a first-time user makes one (experiments/README.md, "Your own study"), run literally and
# without a terminal: vri-run --new writes it, it runs as written with a progress line per step, and gives
# its table and chart; the manifest says what the file left to defaults; --new refuses to overwrite.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
bin=$VRI_BIN
export PATH="$bin:$PATH"

# The walkthrough's commands, as the README gives them.
vri-run --new hydrogen 2> new.txt
vri-tf --check hydrogen-tf.yaml > check.txt
vri-run hydrogen.yaml 2> run.txt
head -n 3 results/hydrogen/speed.md > /dev/null

for f in hydrogen.yaml hydrogen-tf.yaml hydrogen-plot.yaml; do
    grep -q "^vri-run: wrote $f$" new.txt || fail "--new did not say it wrote $f: $(cat new.txt)"
done
grep -q "^hydrogen-tf.yaml: 5 points" check.txt || fail "vri-tf --check: $(cat check.txt)"
steps=$(grep -c ': start ' run.txt) || fail "no progress lines: $(cat run.txt)"
[ "$(grep -c ': ran vri-' run.txt)" -eq "$steps" ] || fail "not a ran line per started step: $(cat run.txt)"
grep -q "^vri-run: hydrogen: $steps steps, $steps ran, 0 cached" run.txt || fail "summary: $(cat run.txt)"

# The table: a row per method run, each with its time and error; the chart: a PNG beside its SVG.
for run in riemann-h2 riemann-h0.125 coupled-eps0.01 coupled-eps0.0001; do
    grep -qE "^\| $run \| (riemann|coupled) double \| [0-9.e+-]+ \|" results/hydrogen/speed.md ||
        fail "no row for $run: $(cat results/hydrogen/speed.md)"
done
[[ $(head -c 8 results/hydrogen/speed.png | od -An -tx1 | tr -d ' ') == 89504e470d0a1a0a ]] || fail "speed.png is not a PNG"
grep -q "<svg" results/hydrogen/speed.svg || fail "no speed.svg"
grep -q '"paper: none (an own study)"' results/hydrogen/manifest.json || fail "the manifest lacks the defaults"
grep -q "\"scene 'field': convention cell, the tools' default\"" results/hydrogen/manifest.json ||
    fail "the manifest does not say the convention was defaulted"

# Run again: all cached. --new over an existing study writes nothing and says why.
vri-run hydrogen.yaml 2> again.txt
grep -q "^vri-run: hydrogen: $steps steps, 0 ran, $steps cached" again.txt || fail "rerun: $(cat again.txt)"
cp hydrogen.yaml before.yaml
if vri-run --new hydrogen 2> exists.txt; then fail "--new overwrote a study"; fi
[ "$(wc -l < exists.txt)" -eq 1 ] && grep -q "^vri-run: error: --new: hydrogen.yaml exists" exists.txt || fail "$(cat exists.txt)"
cmp hydrogen.yaml before.yaml || fail "--new changed hydrogen.yaml"
if vri-run --new "" 2> bad.txt; then fail "--new took no name"; fi
grep -q "^vri-run: error: --new: expected a study's name (NAME.yaml is written), got nothing" bad.txt || fail "$(cat bad.txt)"
if vri-run --new "a b" 2> bad.txt; then fail "--new took an unsafe name"; fi
grep -q "^vri-run: error: --new: 'a b' must be letters" bad.txt || fail "$(cat bad.txt)"
[ ! -e "a b.yaml" ] || fail "--new wrote an unsafe name"
# A full disk (a file size limit of 1 KB: the TF and the plot fit, the experiment does not) places no part.
if bash -c 'ulimit -f 1 && exec "$@"' limited vri-run --new helium 2> full.txt; then fail "--new wrote past the limit"; fi
[ "$(wc -l < full.txt)" -eq 1 ] &&
    grep -q "^vri-run: error: --new: .*helium.yaml: cannot write: File too large (nothing of the study was written)$" full.txt ||
    fail "$(cat full.txt)"
for f in helium.yaml helium-tf.yaml helium-plot.yaml; do [ ! -e "$f" ] || fail "--new left $f on a full disk"; done
[ -z "$(ls -A | grep -F '.helium')" ] || fail "--new left temporary files: $(ls -A | grep -F '.helium')"
echo "new study: written, $steps steps ran with progress lines, table and chart made, rerun cached"
