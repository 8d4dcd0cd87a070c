#!/usr/bin/env bash
# OpenVDB is a module io loads for .vdb files (libvri/io/vdb_module.h): no tool links it (it cost every
# process some 65 ms of start-up); the module writes and reads .vdb; a tool without the module beside it
# says so in one line naming where it looked, and still reads and writes every other format.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
command -v readelf > /dev/null || fail "readelf (binutils) is missing"
for tool in "$VRI_BIN"/vri-*; do
    head -c 4 "$tool" | grep -q ELF || continue  # the peer adapters are scripts
    if readelf -d "$tool" | grep 'NEEDED.*libopenvdb' > /dev/null; then fail "$(basename "$tool") links OpenVDB"; fi
done
readelf -d "$VRI_BIN/vri-convert" | grep -q 'NEEDED' || fail "readelf lists no library of vri-convert"

head -c 60 /dev/urandom > v_5x4x3_uint8.raw
"$VRI_BIN/vri-convert" -q v_5x4x3_uint8.raw v.vdb || fail "vri-convert cannot write a .vdb"
"$VRI_BIN/vri-convert" -q v.vdb back.nhdr || fail "vri-convert cannot read its .vdb"
cmp -s v_5x4x3_uint8.raw back.raw || fail "the .vdb did not come back bit for bit"

# (Skipped where vri is installed system-wide, whose module the tool would then find.)
mkdir -p alone/bin && cp "$VRI_BIN/vri-convert" alone/bin/
installed=$(strings "$VRI_BIN/vri-convert" | grep -m1 '^/.*/vri$' || true)
if [ -n "$installed" ] && [ -e "$installed/libvri-vdb.so" ]; then echo "vri installed in $installed: skipping the missing-module case"; exit 0; fi
rc=0
alone/bin/vri-convert -q v.vdb alone.nhdr 2> err.txt || rc=$?
[ "$rc" -eq 1 ] && [ "$(wc -l < err.txt)" -eq 1 ] || { cat err.txt >&2; fail "vri-convert without the module: exit $rc"; }
grep -q "^vri-convert: error: v.vdb: cannot read volume: .vdb files need vri's OpenVDB module: libvri-vdb.so not found (looked for .*alone/lib.*/vri/libvri-vdb.so" err.txt ||
    { cat err.txt >&2; fail "the message does not say what is missing and where"; }
alone/bin/vri-convert -q v_5x4x3_uint8.raw alone.nhdr || fail "vri-convert without the OpenVDB module cannot convert a raw file"
echo "vdb_module: all checks passed"
