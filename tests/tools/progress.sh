#!/usr/bin/env bash
# Progress without a terminal, as a log or CI sees it: vri-run prints a line when each step starts and
# one when it ends (ran, with its time, or cached), -q prints nothing, and vri-render --repeat a line per
# frame. stderr goes to a file, so none of these runs has a terminal.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
bin=$VRI_BIN src=$VRI_SOURCE

# Paper A's Fig. 4 at its quick size: 8 steps, no data set needed.
"$bin/vri-run" --quick --results out "$src/experiments/paper-a-fig4.yaml" 2> first.txt
steps=$(grep -c ': start ' first.txt) || fail "no start lines: $(cat first.txt)"
[ "$steps" -ge 2 ] || fail "expected a start line per step: $(cat first.txt)"
[ "$(grep -cE '^vri-run: paper-a-fig4 \[[0-9]+/'"$steps"'\] [0-9.]+ s: ran vri-[a-z0-9-]+ [^ ]+ \([0-9.]+ s\)$' first.txt)" -eq "$steps" ] ||
    fail "expected a 'ran ... (N s)' line per step: $(cat first.txt)"
# Every started step is one that ended, and the last line before the summary counts all of them.
diff <(sed -n 's/.*: start \(.*\)$/\1/p' first.txt | sort) <(sed -n 's/.*: ran \(.*\) (.*$/\1/p' first.txt | sort) ||
    fail "the started steps are not the finished ones"
grep -q "\[$steps/$steps\] .*: ran " first.txt || fail "no line counts $steps/$steps: $(cat first.txt)"
grep -q "^vri-run: paper-a-fig4: $steps steps, $steps ran, 0 cached" first.txt || fail "summary: $(cat first.txt)"

# The manifest records the machine's load when each step started and ended.
[ "$(grep -c '"load_average": {' out/paper-a-fig4/manifest.json)" -eq "$steps" ] ||
    fail "not a load average per step in the manifest"

# Again: every step cached, said per step with the time of the run that made it; nothing starts.
"$bin/vri-run" --quick --results out "$src/experiments/paper-a-fig4.yaml" 2> second.txt
[ "$(grep -c ': cached vri-.* s when it ran)$' second.txt)" -eq "$steps" ] || fail "cached lines: $(cat second.txt)"
! grep -q ': start ' second.txt || fail "a cached step started: $(cat second.txt)"

# -q: nothing at all on stderr.
"$bin/vri-run" -q --force --quick --results out "$src/experiments/paper-a-fig4.yaml" 2> quiet.txt
[ ! -s quiet.txt ] || fail "-q printed: $(cat quiet.txt)"

# vri-render --repeat: a line per frame, warm-up frames named so; -q silences them.
render=("$bin/vri-render" --field linear --convention node --tf "$src/experiments/tf/paper-a-linear.yaml"
        --size 16x12 --step 0.5 -o r.exr)
"${render[@]}" --warm-up 1 --repeat 3 2> frames.txt
grep -qE '^vri-render: warm-up frame 1 of 1: [0-9.e+-]+ s$' frames.txt || fail "warm-up line: $(cat frames.txt)"
for k in 1 2 3; do
    grep -qE "^vri-render: frame $k of 3: [0-9.e+-]+ s$" frames.txt || fail "frame $k line: $(cat frames.txt)"
done
"${render[@]}" --warm-up 1 --repeat 3 -q 2> frames-quiet.txt
[ ! -s frames-quiet.txt ] || fail "-q printed: $(cat frames-quiet.txt)"
"${render[@]}" 2> one-frame.txt
! grep -q 'frame' one-frame.txt || fail "a single frame needs no frame line: $(cat one-frame.txt)"
echo "progress: $steps start and ran lines, cached lines, frame lines, -q silent"
