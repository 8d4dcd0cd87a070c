#!/usr/bin/env bash
# Volume files whose few bytes claim gigabytes, and stacks cut short (issue 29 items 5 and 8): gzip NRRD
# and MetaImage whose header claims more than the stream could plausibly hold (256 times its size, or
# 256 MiB) or than it does hold, a TIFF of a few bytes claiming 4 GiB of pages; TIFF stacks cut in a
# directory or in a strip, strips shorter than their page, a chain of pages that loops. Each case: the exit code, the one stderr line
# naming the file (and page), an unchanged work directory (lib/bad_input.sh) and a peak resident memory
# under 256 MiB (GNU time), however much the file claims.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
source "$(dirname "${BASH_SOURCE[0]}")/lib/bad_input.sh"
python=/usr/bin/python3
convert="$VRI_BIN/vri-convert"
E='^vri-convert: error: '

# (Each command runs under timeout 20: GNU time runs programs, not shell functions.)

# --- inputs, made before the cases: the work directory must stay as it is from here on ---
"$python" - <<'PY'
import struct, zlib
# A stream of 100 zero bytes, 12 bytes compressed, behind headers claiming far more.
small = zlib.compress(bytes(100))
open("small.gz", "wb").write(small)
def nhdr(name, sizes, type="uint8", extra=""):
    open(name, "w").write("NRRD0004\ntype: %s\ndimension: 3\nsizes: %s\nendian: little\nencoding: gzip\n%s"
                          % (type, sizes, extra))
nhdr("tiny.nhdr", "1600 1600 1600", extra="data file: small.gz\n")
nhdr("tiny16.nhdr", "1024 1024 1024", "uint16", "data file: small.gz\n")
nhdr("tiny64.nhdr", "512 512 512", "double", "data file: small.gz\n")
# Within 256 MiB, so read: the stream's 100 bytes cost what they are, not the 200 MiB claimed.
nhdr("floor.nhdr", "1024 1024 200", extra="data file: small.gz\n")
nhdr("floor32.nhdr", "1024 1024 60", "float", "data file: small.gz\n")
open("tiny.nrrd", "wb").write(b"NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2048 2048 2048\nencoding: gzip\n\n" + small)
# A bomb: 2 GiB of zeros in 2 MB (zlib's ratio of 1028), and half of it (512 MiB claimed from 1 MB).
c = zlib.compressobj(9)
bomb = b"".join([c.compress(bytes(1 << 24)) for _ in range(128)] + [c.flush()])
half = bomb[: len(bomb) // 2]
open("bomb.nrrd", "wb").write(b"NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2048 1024 1024\nencoding: gzip\n\n" + bomb)
open("half.nrrd", "wb").write(b"NRRD0004\ntype: uint8\ndimension: 3\nsizes: 1024 1024 512\nencoding: gzip\n\n" + half)
mha = "ObjectType = Image\nNDims = 3\nDimSize = %s\nElementType = %s\nCompressedData = True\nElementDataFile = %s\n"
open("bomb.mha", "wb").write((mha % ("2048 1024 1024", "MET_UCHAR", "LOCAL")).encode() + bomb)
open("tiny.mha", "wb").write((mha % ("4096 4096 4096", "MET_FLOAT", "LOCAL")).encode() + small)
open("tiny.mhd", "w").write(mha % ("2000 2000 2000", "MET_USHORT", "small.gz"))
open("floor.mhd", "w").write(mha % ("1024 1024 100", "MET_USHORT", "small.gz"))

# TIFF: pages of uncompressed strips, each page's data then its directory (tiffcp's order).
def tiff(name, w, h, pages=1, strip=None, bits=8, cut=None, loop=False):
    out = bytearray(b"II*\0\0\0\0\0")
    ifds = []
    for p in range(pages):
        size = w * h * bits // 8 if strip is None else strip
        at = len(out)
        out += bytes((p + i) % 251 for i in range(min(size, 1 << 16)))
        tags = [(256, 4, w), (257, 4, h), (258, 3, bits), (259, 3, 1), (262, 3, 1), (273, 4, at),
                (277, 3, 1), (278, 4, h), (279, 4, size)]
        ifds.append(len(out))
        out += struct.pack("<H", len(tags)) + b"".join(struct.pack("<HHII", t, k, 1, v) for t, k, v in tags) + bytes(4)
    struct.pack_into("<I", out, 4, ifds[0])
    for a, b in zip(ifds, ifds[1:] + ([ifds[0]] if loop else [])):
        struct.pack_into("<I", out, a + 2 + 12 * 9, b)
    open(name, "wb").write(out[:cut] if cut else out)
    return len(out)
tiff("huge.tif", 65535, 65535, strip=10)                 # 4 GiB claimed by 132 bytes
tiff("pages.tif", 4096, 4096, pages=64, strip=16)        # 64 pages of 16 MiB, 10 KB in all
tiff("many.tif", 65535, 65535, pages=8, strip=16)        # 32 GiB: over the byte limit itself
tiff("short.tif", 64, 64, pages=3, strip=100)            # strips of 100 bytes where a page needs 4096
whole = tiff("stack.tif", 16, 8, pages=4)
tiff("cut-ifd.tif", 16, 8, pages=4, cut=whole - 60)      # the last directory cut in two
tiff("cut-data.tif", 16, 8, pages=4, cut=whole - 200)    # into page 3's strip, before its directory
tiff("cut-mid.tif", 16, 8, pages=4, cut=whole - 330)     # into page 2's directory
tiff("cut-header.tif", 16, 8, pages=4, cut=6)
tiff("loop.tif", 16, 8, pages=3, loop=True)              # page 2 chains back to page 0
open("tf.yaml", "w").write("points: [[0, 0, 0, 0, 0], [1, 1, 1, 1, 1]]\n")
open("text.tif", "w").write("not a TIFF\n")
open("beyond.tif", "wb").write(b"II*\0" + struct.pack("<I", 1 << 20) + bytes(8))
open("entries.tif", "wb").write(b"II*\0" + struct.pack("<IH", 8, 60000) + bytes(8))
PY
# A valid stack written by libtiff (tiffcp), cut short: the cut falls in page 1's strip or directory.
if command -v tiffcp > /dev/null; then
  tiffcp stack.tif libtiff.tif
  head -c $(($(stat -c %s libtiff.tif) * 2 / 3)) libtiff.tif > libtiff-cut.tif
  rm libtiff.tif
fi

# --- item 5: claimed sizes against the limit and the compressed size, buffers grown as data arrive ---
ratio='\(256 times its size or 256 MiB; set VRI_MAX_BYTES to allow more\)$'
bad 1 "${E}tiny\.nhdr: data file small\.gz: 1600x1600x1600 uint8: needs 4096000000 bytes, limit 268435456 for compressed data of 12 bytes $ratio" -- timeout 20 "$convert" --info tiny.nhdr
bad 1 "${E}tiny16\.nhdr: data file small\.gz: 1024x1024x1024 uint16: needs 2147483648 bytes, limit 268435456 for compressed data of 12 bytes" -- timeout 20 "$convert" --info tiny16.nhdr
bad 1 "${E}tiny64\.nhdr: data file small\.gz: 512x512x512 float64: needs 1073741824 bytes, limit 268435456" -- timeout 20 "$convert" --info tiny64.nhdr
bad 1 "${E}tiny\.nrrd: 2048x2048x2048 uint8: needs 8589934592 bytes, limit 268435456 for compressed data of 12 bytes" -- timeout 20 "$convert" --info tiny.nrrd
bad 1 "${E}floor\.nhdr: data file small\.gz: gzip data of 1024x1024x200 uint8: the compressed data hold 100 bytes, expected 209715200$" -- timeout 20 "$convert" --info floor.nhdr
bad 1 "${E}floor32\.nhdr: data file small\.gz: gzip data of 1024x1024x60 float32: the compressed data hold 100 bytes, expected 251658240$" -- timeout 20 "$convert" --info floor32.nhdr
bad 1 "${E}bomb\.nrrd: 2048x1024x1024 uint8: needs 2147483648 bytes, limit 534340608 for compressed data of 2087268 bytes $ratio" -- timeout 20 "$convert" --info bomb.nrrd
bad 1 "${E}half\.nrrd: 1024x1024x512 uint8: needs 536870912 bytes, limit 268435456 for compressed data of 1043634 bytes" -- timeout 20 "$convert" --info half.nrrd
bad 1 "${E}bomb\.mha: 2048x1024x1024 uint8: needs 2147483648 bytes, limit 534340608 for compressed data of 2087268 bytes $ratio" -- timeout 20 "$convert" --info bomb.mha
bad 1 "${E}tiny\.mha: 4096x4096x4096 float32: needs 274877906944 bytes, limit 17179869184 \(VRI_MAX_BYTES\)$" -- timeout 20 "$convert" --info tiny.mha
bad 1 "${E}tiny\.mhd: ElementDataFile small\.gz: 2000x2000x2000 uint16: needs 16000000000 bytes, limit 268435456 for compressed data of 12 bytes" -- timeout 20 "$convert" --info tiny.mhd
bad 1 "${E}floor\.mhd: ElementDataFile small\.gz: gzip data of 1024x1024x100 uint16: the compressed data hold 100 bytes, expected 209715200$" -- timeout 20 "$convert" --info floor.mhd
# VRI_MAX_BYTES states the limit: the ratio steps aside, the stated limit holds.
bad 1 "${E}bomb\.nrrd: 2048x1024x1024 uint8: needs 2147483648 bytes, limit 1000000000 \(VRI_MAX_BYTES\)$" -- env VRI_MAX_BYTES=1000000000 "$convert" --info bomb.nrrd
# ... and the buffer grows with the stream: 100 bytes inflated cost no 4 GB.
bad 1 "${E}tiny\.nhdr: data file small\.gz: gzip data of 1600x1600x1600 uint8: the compressed data hold 100 bytes, expected 4096000000$" -- env VRI_MAX_BYTES=5000000000 "$convert" --info tiny.nhdr
# Every tool that reads a volume.
bad 1 "^vri-render: error: bomb\.mha: 2048x1024x1024 uint8: needs 2147483648 bytes" -- timeout 20 "$VRI_BIN/vri-render" --volume bomb.mha --tf tf.yaml -q -o out.exr
bad 1 "^vri-reference: error: tiny\.nhdr: data file small\.gz: 1600x1600x1600 uint8: needs" -- timeout 20 "$VRI_BIN/vri-reference" --volume tiny.nhdr --tf tf.yaml -q -o out.exr

# --- TIFF: the pages' claimed size against the limit and the file's size ---
bad 1 "${E}huge\.tif: 65535x65535x1 uint8: needs 4294836225 bytes, limit 268435456 for a file of 132 bytes $ratio" -- timeout 20 "$convert" --info huge.tif
bad 1 "${E}pages\.tif: 4096x4096x64 uint8: needs 1073741824 bytes, limit 268435456 for a file of [0-9]+ bytes" -- timeout 20 "$convert" --info pages.tif
bad 1 "${E}many\.tif: 65535x65535x8 uint8: needs 34358689800 bytes, limit 17179869184 \(VRI_MAX_BYTES\)$" -- timeout 20 "$convert" --info many.tif
bad 1 "^vri-render: error: huge\.tif: 65535x65535x1 uint8: needs" -- timeout 20 "$VRI_BIN/vri-render" --volume huge.tif --tf tf.yaml -q -o out.exr

# --- item 8: a stack cut short is an error naming the page, never fewer pages or pages of zeros ---
bad 1 "${E}cut-ifd\.tif: page 3: its directory at byte 862 \(9 entries\) ends beyond the file's end \(916 bytes\)$" -- timeout 20 "$convert" --info cut-ifd.tif
bad 1 "${E}cut-data\.tif: page 3: its directory at byte 862 lies beyond the file's end \(776 bytes\)$" -- timeout 20 "$convert" --info cut-data.tif
bad 1 "${E}cut-mid\.tif: page 2: its directory at byte 620 \(9 entries\) ends beyond the file's end \(646 bytes\)$" -- timeout 20 "$convert" --info cut-mid.tif
bad 1 "${E}cut-header\.tif: the header ends at byte 6, before its first page$" -- timeout 20 "$convert" --info cut-header.tif
bad 1 "${E}short\.tif: page 0: .*got [0-9]+ bytes, expected 4096$" -- timeout 20 "$convert" --info short.tif
bad 1 "${E}loop\.tif: page [0-9]+: its directory at byte [0-9]+ is an earlier page's \(the chain of pages loops\)$" -- timeout 20 "$convert" --info loop.tif
bad 1 "${E}text\.tif: not a TIFF file \(expected II or MM as its first bytes\)$" -- timeout 20 "$convert" --info text.tif
bad 1 "${E}beyond\.tif: page 0: its directory at byte 1048576 lies beyond the file's end \(16 bytes\)$" -- timeout 20 "$convert" --info beyond.tif
bad 1 "${E}entries\.tif: page 0: its directory at byte 8 claims 60000 entries, more than the file's 18 bytes hold$" -- timeout 20 "$convert" --info entries.tif
if [ -f libtiff-cut.tif ]; then
  bad 1 "${E}libtiff-cut\.tif: page [0-9]: " -- timeout 20 "$convert" --info libtiff-cut.tif
fi
bad 1 "^vri-render: error: cut-ifd\.tif: page 3: " -- timeout 20 "$VRI_BIN/vri-render" --volume cut-ifd.tif --tf tf.yaml -q -o out.exr
# The whole stack reads, all four pages of it.
"$convert" --info --json stack.tif | "$python" -c 'import json, sys; assert json.load(sys.stdin)["dims"] == [16, 8, 4]' ||
  fail "stack.tif: not read as 16x8x4"

bad_done
