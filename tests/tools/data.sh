#!/usr/bin/env bash
# vri-data (`make data`) end to end on a tiny catalog: a good file is verified, a corrupted one is a
# MISMATCH, a missing one is downloaded (from a file:// URL, so no network is needed) and checked,
# a bad download is refused and removed; then the project's catalog against $VRI_DATA_DIR if present.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"

data="$VRI_BIN/vri-data"

mkdir -p published volumes
printf 'abcd' > published/tiny.raw
printf 'abce' > published/wrong.raw
digest=$(sha512sum published/tiny.raw | cut -d' ' -f1)
entry() {  # entry NAME URL-FILE STATUS
    printf '  - name: %s\n    file: %s.raw\n    dims: [2, 2, 1]\n    type: uint8\n    sha512: %s\n' "$1" "$1" "$digest"
    printf '    url: file://%s/published/%s\n    status: %s\n    note: four bytes\n' "$PWD" "$2" "$3"
}
{ echo "datasets:"; entry tiny tiny.raw exact; } > catalog.yaml

run_data() {  # sets rc; stdout in out.txt, stderr in err.txt
    rc=0
    VRI_DATA_DIR=volumes "$data" --catalog catalog.yaml "$@" >out.txt 2>err.txt || rc=$?
}

grep -q "Example" <<<"$("$data" --help)" || fail "--help shows no example"

# Missing, not downloaded.
run_data --no-download
[[ $rc -ne 0 ]] || fail "a missing dataset passed"
grep -q '^MISSING *tiny' out.txt || fail "no MISSING line: $(cat out.txt)"
[ "$(wc -l < err.txt)" -eq 1 ] && grep -q "error: 1 dataset is missing or mismatched in volumes" err.txt ||
    fail "missing without a one-line error: $(cat err.txt)"

# Missing, downloaded and verified.
if command -v curl >/dev/null || command -v wget >/dev/null; then
    run_data
    [[ $rc -eq 0 ]] || fail "download: exit $rc: $(cat out.txt err.txt)"
    grep -q '^downloaded *tiny' out.txt || fail "no downloaded line: $(cat out.txt)"
    cmp published/tiny.raw volumes/tiny.raw || fail "downloaded file differs"
    # A download with the wrong digest is refused and leaves nothing behind.
    { echo "datasets:"; entry wrong wrong.raw exact; } > catalog.yaml
    run_data
    [[ $rc -ne 0 ]] || fail "a wrong download passed"
    grep -q '^MISMATCH *wrong' out.txt || fail "no MISMATCH line for a wrong download: $(cat out.txt)"
    [[ -z $(ls -A volumes | grep -v '^tiny.raw$') ]] || fail "a wrong download was left: $(ls -A volumes)"
    { echo "datasets:"; entry tiny tiny.raw exact; } > catalog.yaml
else
    cp published/tiny.raw volumes/tiny.raw
fi

# Present and good.
run_data --no-download
[[ $rc -eq 0 ]] || fail "good file: exit $rc: $(cat out.txt err.txt)"
grep -q '^verified *tiny' out.txt || fail "no verified line: $(cat out.txt)"

# Corrupted: one byte changed.
printf 'abcX' > volumes/tiny.raw
run_data --no-download
[[ $rc -ne 0 ]] || fail "a corrupted file passed"
grep -q '^MISMATCH *tiny.*SHA-512' out.txt || fail "no MISMATCH line: $(cat out.txt)"

# Reconstructed: its digest is not a published one; a differing copy is reported, not failed.
{ echo "datasets:"; entry tiny tiny.raw reconstructed; } > catalog.yaml
run_data --no-download
[[ $rc -eq 0 ]] || fail "reconstructed dataset failed: $(cat out.txt)"
grep -q '^ok *tiny.*not checked.*\[reconstructed\]' out.txt || fail "reconstructed: $(cat out.txt)"

# A malformed catalog: one line with file:line:col, non-zero exit.
{ echo "datasets:"; entry tiny tiny.raw exact; echo "    colour: red"; } > catalog.yaml
run_data --no-download
[[ $rc -ne 0 ]] || fail "a malformed catalog passed"
[[ $(wc -l <err.txt) -eq 1 ]] || fail "malformed catalog: not one line: $(cat err.txt)"
grep -q "^vri-data: error: catalog.yaml:10:5: unknown key 'colour'" err.txt || fail "malformed catalog: $(cat err.txt)"

# --only with an unknown name.
{ echo "datasets:"; entry tiny tiny.raw exact; } > catalog.yaml
run_data --only tiny,huge
grep -q "unknown dataset 'huge'" err.txt || fail "--only huge: $(cat err.txt)"

# The project's catalog against the shared volumes, when this machine has them.
shared="${VRI_DATA_DIR:-$VRI_SOURCE/../shared/data/volumes}"
if [[ -d $shared ]]; then
    rc=0
    VRI_DATA_DIR="$shared" "$data" --catalog "$VRI_SOURCE/experiments/datasets.yaml" --no-download >out.txt 2>&1 || rc=$?
    cat out.txt
    [[ $rc -eq 0 ]] || fail "the project's datasets do not check out in $shared"
fi
echo "data: all checks passed"
