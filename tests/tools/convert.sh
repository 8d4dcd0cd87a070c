#!/usr/bin/env bash
# vri-convert end to end: raw -> vdb -> raw is byte-exact, --info and --help work, and bad input
# fails with one line on stderr and no output file.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"

convert="$VRI_BIN/vri-convert"

# 4x3x2 uint8 with zeros, small and large values.
printf '\000\001\002\003\000\000\377\200\000\012\013\014\000\000\000\000\100\101\102\000\000\000\000\376' > tiny_4x3x2_uint8.raw
[ "$(stat -c %s tiny_4x3x2_uint8.raw)" -eq 24 ] || fail "fixture is not 24 bytes"

"$convert" -q tiny_4x3x2_uint8.raw tiny.vdb
"$convert" -q tiny.vdb back.raw
cmp tiny_4x3x2_uint8.raw back.raw

# Explicit layout, big-endian uint16 through .nhdr and .vdb.
head -c 48 /dev/urandom > noise.bin
"$convert" -q noise.bin noise.nhdr --dims 4,3,2 --type uint16 --byte-order big --spacing 0.5,1,2
"$convert" -q noise.nhdr noise.vdb
"$convert" -q noise.vdb noise_le.raw
"$convert" -q noise_le.raw copy.nhdr --dims 4,3,2 --type uint16
"$convert" -q copy.nhdr copy2.dat
dd if=noise.bin conv=swab status=none | cmp - noise.raw
cmp noise_le.raw noise.raw
cmp noise_le.raw copy2.raw

info=$("$convert" --info tiny.vdb)
grep -q "4 x 3 x 2" <<<"$info" || fail "--info does not show the dims: $info"
grep -q "uint8" <<<"$info" || fail "--info does not show the voxel type: $info"
grep -q "histogram" <<<"$info" || fail "--info does not show a histogram: $info"
grep -q "^active       12 voxels not 0, in 1 of 1 bricks of 8^3" <<<"$info" || fail "--info active voxels: $info"
# 17 voxels along x: bricks 0..7, 8..15, 16; only voxel 16 is not 0.
printf '\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\007' > line_17x1x1_uint8.raw
json=$("$convert" --info --json line_17x1x1_uint8.raw)
grep -q '"active_voxels": 1,' <<<"$json" || fail "--json active_voxels: $json"
grep -q '"active_bricks": 1,' <<<"$json" || fail "--json active_bricks: $json"
grep -q '"bricks": 3,' <<<"$json" || fail "--json bricks: $json"
json=$("$convert" --info --json noise.nhdr)
grep -q '"voxel_type": "uint16"' <<<"$json" || fail "--json does not show the voxel type: $json"

help=$("$convert" --help)
grep -q "Example" <<<"$help" || fail "--help shows no example"

# A raw file one byte short: non-zero exit, one line naming the file, nothing written.
head -c 23 tiny_4x3x2_uint8.raw > short_4x3x2_uint8.raw
if "$convert" short_4x3x2_uint8.raw short.vdb 2> err.txt; then fail "a short raw file was accepted"; fi
[ "$(wc -l < err.txt)" -eq 1 ] || fail "expected one line on stderr, got: $(cat err.txt)"
grep -q "short_4x3x2_uint8.raw" err.txt || fail "the error does not name the file: $(cat err.txt)"
[ ! -e short.vdb ] || fail "short.vdb was written despite the error"
[ -z "$(ls -A | grep -i '\.tmp\.')" ] || fail "a temporary file was left behind"

if "$convert" noise.bin x.vdb --dims 4,3,2 --type int7 2> err.txt; then fail "--type int7 was accepted"; fi
grep -q "int7" err.txt || fail "the error does not name the type: $(cat err.txt)"
[ ! -e x.vdb ] || fail "x.vdb was written despite the error"

if "$convert" missing.raw x.vdb 2> err.txt; then fail "a missing file was accepted"; fi
grep -q "missing.raw: no such file" err.txt || fail "unexpected error for a missing file: $(cat err.txt)"

# tiny.nhdr would write its voxels to tiny.raw: refuse when that is the input.
cp tiny_4x3x2_uint8.raw tiny.raw
rc=0; "$convert" tiny.raw tiny.nhdr --dims 4,3,2 --type uint8 2> err.txt || rc=$?
[ "$rc" -eq 64 ] || fail "overwriting the input: exit $rc, expected 64"
grep -q "^vri-convert: error: output's raw file 'tiny.raw' is the same file as input 'tiny.raw'$" err.txt ||
  fail "unexpected error when overwriting the input: $(cat err.txt)"
[ ! -e tiny.nhdr ] || fail "tiny.nhdr was written despite the error"

echo "convert: ok"
