# OpenImageIO is a module loaded when a file needs it (libvri/io/oiio_module.h): no tool links it, since it
# cost every process 0.7-1 s of start-up. The module serves the formats other than EXR and PNG; a tool that
# cannot find it says so in one line naming where it looked, and still reads and writes EXR.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
command -v oiiotool > /dev/null || { echo "oiiotool not installed: skipping"; exit 77; }

for tool in "$VRI_BIN"/vri-*; do
    head -c 4 "$tool" | grep -q ELF || continue  # the peer adapters are scripts
    if readelf -d "$tool" | grep 'NEEDED.*libOpenImageIO' > /dev/null; then fail "$(basename "$tool") links OpenImageIO"; fi
done

oiiotool --pattern constant:color=0.5,0.2,0.1,1 8x6 4 -d float -o a.exr
oiiotool --pattern constant:color=0.5,0.25,0.1,1 8x6 4 -d float -o b.exr
oiiotool a.exr -o a.tif
# Through the module: a TIFF read, a TIFF written (the difference image) and read back.
"$VRI_BIN/vri-diff" a.exr a.tif --fail 0 > /dev/null || fail "a.tif did not read as a.exr"
"$VRI_BIN/vri-diff" a.exr b.exr --diff-image d.tif > /dev/null || true
[ -s d.tif ] || fail "no difference image d.tif"
"$VRI_BIN/vri-diff" d.tif d.tif --fail 0 > /dev/null || fail "d.tif unreadable"

# A tool without the module beside it: EXR works, a TIFF is one line saying what is missing and where.
# (Skipped where vri is installed system-wide, whose module the tool would then find.)
mkdir -p alone/bin && cp "$VRI_BIN/vri-diff" alone/bin/
installed=$(strings "$VRI_BIN/vri-diff" | grep -m1 '^/.*/vri$' || true)
if [ -n "$installed" ] && [ -e "$installed/libvri-oiio.so" ]; then echo "vri installed in $installed: skipping the missing-module case"; exit 0; fi
alone/bin/vri-diff a.exr b.exr > /dev/null || [ $? -eq 3 ] || fail "vri-diff without the module cannot compare EXRs"
rc=0
alone/bin/vri-diff a.exr a.tif > out.txt 2> err.txt || rc=$?
[ "$rc" -eq 1 ] || fail "vri-diff without the module on a TIFF: exit $rc, expected 1"
[ "$(wc -l < err.txt)" -eq 1 ] || { cat err.txt >&2; fail "not one line"; }
grep -q "a.tif: cannot read image: this format needs vri's OpenImageIO module: libvri-oiio.so not found (looked for .*alone/lib.*/vri/libvri-oiio.so" err.txt ||
    { cat err.txt >&2; fail "the message does not say what is missing and where"; }
echo "oiio_module: all checks passed"
