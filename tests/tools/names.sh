#!/usr/bin/env bash
# Names and paths are data, never code, and vri-run keeps to its folder: hostile names through
# vri-plot and vri-run (no marker file appears; a name with an apostrophe works), two vri-run on one
# folder (one runs, the other is refused naming the first; the manifest matches the files), stale
# temporary files removed and live ones kept, and vri-run killed with -9 mid-way, again and again:
# no final file is ever half-written and a rerun gives what an uninterrupted run gives.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
bin=$VRI_BIN

markers() { find "$VRI_SCRATCH" -name 'marker*' | head -5; }

# Every output a manifest lists has the SHA-512 recorded for it.
manifest_matches() {
  local manifest=$1 path sha
  [ -s "$manifest" ] || fail "$manifest: missing"
  while IFS=$'\t' read -r path sha; do
    [ "$(sha512sum < "$path" | cut -d' ' -f1)" = "$sha" ] || fail "$manifest: $path does not match its digest"
  done < <(jq -r '.steps[] | .outputs[] | [.path, .sha512] | @tsv' "$manifest")
}

# Nothing in a results folder is half-written: images end as images end, JSON parses, and every
# file that the uninterrupted run also made is the same (EXR pixels; the files without times, byte for byte).
complete_like() {
  local dir=$1 ref=$2 f name
  for f in "$dir"/*; do
    name=$(basename "$f")
    case "$name" in
      *.png) [ "$(tail -c 8 "$f" | od -An -tx1 | tr -d ' \n')" = "49454e44ae426082" ] || fail "$f: not a whole PNG";;
      *.json) jq empty "$f" 2> /dev/null || fail "$f: not whole JSON";;
      *.svg) tail -c 10 "$f" | grep -q '</svg>' || fail "$f: not a whole SVG";;
    esac
    case "$name" in
      *.exr) "$bin/vri-diff" "$ref/$name" "$f" --fail 0 > /dev/null || fail "$f: differs from $ref/$name";;
      *.png | *.csv | *.md | *.svg) cmp -s "$ref/$name" "$f" || fail "$f: differs from $ref/$name";;
    esac
  done
}

# --- vri-plot: hostile output names and titles --------------------------------------------------
printf 'x,y\n1,2\n2,3\n' > d.csv
cat > spec.yaml <<'YAML'
title: "it's ';system('touch marker1');x=' `touch marker2` $(touch marker3)"
series:
  - {file: d.csv, x: x, y: y, label: "a'b"}
YAML
for name in "p';system('touch marker4');x='" "q\`touch marker5\`" "r\$(touch marker6)" $'s\nsystem("touch marker7")' \
            "it's a figure" "unicode-é"; do
  mkdir -p "out/$name"
  "$bin/vri-plot" spec.yaml -o "out/$name/$name.png" 2> plot-err.txt || fail "vri-plot -o '$name': $(cat plot-err.txt)"
  [ "$(head -c 4 "out/$name/$name.png" | od -An -tx1 | tr -d ' \n')" = "89504e47" ] || fail "'$name': not a PNG"
  grep -q '</svg>' "out/$name/$name.svg" || fail "'$name': no SVG"
done
[ -z "$(markers)" ] || fail "a name ran as code: $(markers)"
grep -q "touch marker1" "out/it's a figure/it's a figure.svg" || fail "the title was not drawn as text"

# --- vri-run: a results root with an apostrophe, a shell and a gnuplot metacharacter ------------
cat > red.yaml <<'YAML'
points:
  - [0.0, 0.0, 0.0, 0.0, 0.0]
  - [1.0, 1.0, 0.2, 0.1, 0.8]
YAML
cat > plot.yaml <<'YAML'
series:
  - {file: rays.csv, x: ray, y: closed_form, label: "it's the closed form"}
YAML
cat > small.yaml <<'YAML'
name: small
title: T
paper: {paper: A, item: Fig. 4, says: a test}
scenes:
  a: {field: linear, field_dims: [5, 5, 5], convention: node, tf: red.yaml, size: [160, 120]}
methods:
  riemann: {placement: [entry, eye], rate: [1, 2]}
comparisons:
  vs: {reference: riemann-entry-r2, diff_image: png}
commands:
  rays: {tool: vri-rays2d, options: {rates: [1, 4]}, outputs: {o: rays.csv, errors: errors.md}}
figures:
  closed-form: {spec: plot.yaml, data: [rays.csv]}
YAML
root="it's \$(touch marker8) \`touch marker9\` ';system('touch marker10')'"
"$bin/vri-run" --results "$root" small.yaml 2> run-err.txt || fail "vri-run under '$root': $(cat run-err.txt)"
[ -s "$root/small/closed-form.png" ] || fail "no figure under '$root'"
[ -z "$(markers)" ] || fail "a name ran as code: $(markers)"
manifest_matches "$root/small/manifest.json"
# --dry-run prints them quoted for a shell: run by hand, they make the same files and run nothing else.
"$bin/vri-run" --dry-run --results "by hand $root" small.yaml > by-hand.sh
bash -e by-hand.sh > /dev/null 2>&1 || fail "the --dry-run commands failed: $(head -3 by-hand.sh)"
cmp "$root/small/rays.csv" "by hand $root/small/rays.csv" || fail "by hand: another rays.csv"
[ -s "by hand $root/small/closed-form.png" ] || fail "by hand: no figure"
[ -z "$(markers)" ] || fail "a printed command ran a name as code: $(markers)"

# A hostile figure name is refused before anything runs.
sed "s/  closed-form:/  \"x';system('touch\${IFS}marker11');x='\":/" small.yaml > hostile.yaml
rc=0; "$bin/vri-run" --results hostile hostile.yaml 2> err.txt || rc=$?
[ "$rc" -eq 1 ] && grep -q "^vri-run: error: hostile.yaml:13:3: figures: a name must be" err.txt || fail "hostile figure: $rc $(cat err.txt)"
[ ! -e hostile ] && [ -z "$(markers)" ] || fail "a refused experiment left something"

# --- two vri-run on one folder ------------------------------------------------------------------
sed -e 's/size: \[160, 120\]/size: [400, 300]/' -e 's/rate: \[1, 2\]/rate: [1, 2, 4, 8]/' small.yaml > slow.yaml
"$bin/vri-run" --results both slow.yaml 2> first.txt &
first=$!
for _ in $(seq 600); do [ "$(cat both/small/.vri-run.lock 2> /dev/null)" = "$first" ] && break; sleep 0.05; done
[ "$(cat both/small/.vri-run.lock)" = "$first" ] || fail "the first vri-run did not take the lock"
rc=0; "$bin/vri-run" --results both slow.yaml 2> second.txt || rc=$?
wait "$first" || fail "the first vri-run failed: $(cat first.txt)"
[ "$rc" -eq 1 ] || fail "the second vri-run exited $rc: $(cat second.txt)"
[ "$(wc -l < second.txt)" -eq 1 ] &&
  grep -q "^vri-run: error: .*both/small: in use by another vri-run (pid $first: .*vri-run --results both slow.yaml); wait" second.txt ||
  fail "lock message: $(cat second.txt)"
manifest_matches both/small/manifest.json
"$bin/vri-run" --results both slow.yaml 2> third.txt || fail "after the first finished: $(cat third.txt)"
grep -q "0 ran" third.txt || fail "a rerun after the lock was released: $(cat third.txt)"

# --- stale temporary files ------------------------------------------------------------------------
dead=4194000
while kill -0 "$dead" 2> /dev/null; do dead=$((dead + 1)); done
touch "both/small/.riemann-eye-r1.tmp.$dead.exr" "both/small/.steps/.rays.tmp.$dead.json" \
      "both/small/.rays.tmp.$$.csv" both/small/.notes.tmp.abc "both/small/.notes.tmp.$dead.txt" \
      "both/small/.riemann-eye-r1.tmp.$dead.exr.bak"
"$bin/vri-run" --results both slow.yaml 2> stale.txt || fail "with stale files: $(cat stale.txt)"
[ ! -e "both/small/.riemann-eye-r1.tmp.$dead.exr" ] && [ ! -e "both/small/.steps/.rays.tmp.$dead.json" ] ||
  fail "a dead process's temporary file is left"
# Only the temporary names of the files the plan writes: a user's look-alikes stay.
[ -e "both/small/.rays.tmp.$$.csv" ] && [ -e both/small/.notes.tmp.abc ] && [ -e "both/small/.notes.tmp.$dead.txt" ] &&
  [ -e "both/small/.riemann-eye-r1.tmp.$dead.exr.bak" ] || fail "a live or foreign file was removed"
[ "$(grep -c "a temporary file of a process that is gone" stale.txt)" -eq 2 ] || fail "stale: $(cat stale.txt)"

# --- kill -9 mid-way, several times ----------------------------------------------------------------
start=$(date +%s%N)
"$bin/vri-run" --jobs 2 --results whole slow.yaml 2> /dev/null || fail "the uninterrupted run failed"
whole_ms=$(( ($(date +%s%N) - start) / 1000000 ))
outputs=$(ls whole/small | wc -l)
# kill_run WHEN: a run into killed/ in its own session, so that kill -9 of the group takes its steps too,
# as a power cut would; killed after WHEN seconds, or once its first output is written (WHEN `output`).
# Every file it left must be whole; counts the kill, and the run stopped mid-way.
kills=0 partial=0
kill_run() {
  setsid "$bin/vri-run" --jobs 2 --results killed slow.yaml 2> /dev/null &
  local victim=$! made
  if [ "$1" = output ]; then
    for _ in $(seq 3000); do
      [ -n "$(ls killed/small 2> /dev/null)" ] || ! kill -0 "$victim" 2> /dev/null && break
      sleep 0.01
    done
  else
    sleep "$1"
  fi
  if kill -9 -- "-$victim" 2> /dev/null || kill -9 "$victim" 2> /dev/null; then kills=$((kills + 1)); fi
  wait "$victim" 2> /dev/null || true
  # Its steps too must be gone (reaped by init, not zombies) before anything looks at their files: a
  # temporary file of a process that still exists is a live one, which the rerun rightly keeps.
  for _ in $(seq 100); do pgrep -s "$victim" > /dev/null || break; sleep 0.1; done
  if [ -d killed/small ]; then
    complete_like killed/small whole/small
    made=$(ls killed/small | wc -l)
    [ "$made" -gt 0 ] && [ "$made" -lt "$outputs" ] && partial=$((partial + 1))
  fi
  return 0
}
# Killed after a share of the whole run's time (the machine may be slow or busy); each rerun skips
# what the runs before it finished, so later kills land further on. A run that finished before its kill
# (the rest of the work was quicker than its share) leaves the folder complete: the next starts from
# nothing, so that at least three runs are killed whatever the machine's speed.
for share in 10 25 15 35 20 45 10 25 15 35 20 45; do
  [ "$kills" -lt 6 ] || break
  before=$kills
  kill_run "$(awk -v ms="$whole_ms" -v share="$share" 'BEGIN { printf "%.3f", ms * share / 100000 }')"
  [ "$kills" -gt "$before" ] || rm -rf killed
done
[ "$kills" -ge 3 ] || fail "only $kills of the runs were still running when killed"
# On a slow machine (a sanitizer build starts each step slowly) every kill timed by the clock may land
# before the first output or after the last: then one more, in an emptied folder, at its first output.
if [ "$partial" -eq 0 ]; then
  rm -rf killed
  kill_run output
fi
[ "$partial" -ge 1 ] || fail "no kill landed mid-way (whole run $whole_ms ms)"
"$bin/vri-run" --jobs 2 --results killed slow.yaml 2> rerun.txt || fail "the rerun after kill -9 failed: $(cat rerun.txt)"
complete_like killed/small whole/small
[ "$(cd killed/small && ls)" = "$(cd whole/small && ls)" ] || fail "the rerun made other files than the whole run"
[ -z "$(find killed/small -name '*.tmp.*')" ] || fail "temporary files left: $(find killed/small -name '*.tmp.*')"
manifest_matches killed/small/manifest.json
echo "names: all checks passed ($kills kills, $partial mid-way, whole run $whole_ms ms)"
