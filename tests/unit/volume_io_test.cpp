#include <doctest/doctest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <string>

#include <unistd.h>
#include <zlib.h>

#include "file_bytes.h"
#include "libvri/io/volume_io.h"
#include "libvri/util/error.h"
#include "libvri/util/format.h"
#include "libvri/util/parse.h"

namespace fs = std::filesystem;
using vri::test::readBytes;

namespace {

// A fresh directory under the system temp directory, removed with everything in it.
struct TempDir {
    fs::path path;
    TempDir() {
        static std::atomic<int> counter{0};
        path = fs::temp_directory_path() /
               ("vri-volume-io-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
        fs::remove_all(path);
        fs::create_directories(path);
    }
    ~TempDir() {
        std::error_code ignored;
        fs::remove_all(path, ignored);
    }
    fs::path operator/(const std::string& name) const { return path / name; }
};

void writeBytes(const fs::path& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary);
    out << bytes;
}

// Values that exercise each type: zeros (most of them, as in real scans), the extremes, and
// for float negative, fractional, -0.0, the extremes and a denormal (NaN is refused at load).
vri::Volume testVolume(glm::ivec3 dims, vri::VoxelType type) {
    vri::Volume volume(dims, type);
    vri::dispatchVoxelType(type, [&](auto t) {
        using T = decltype(t);
        T* values = volume.data<T>();
        for (std::size_t i = 0; i < volume.voxelCount(); ++i) {
            if (i % 3 != 0) continue;  // two thirds stay empty
            if constexpr (std::is_same_v<T, float>)
                values[i] = static_cast<float>(i) * 0.37f - 11.0f;
            else
                values[i] = static_cast<T>(i * 2654435761u);
        }
        if constexpr (std::is_same_v<T, float>) {
            values[1] = -0.0f;
            values[2] = std::numeric_limits<float>::lowest();
            values[4] = std::numeric_limits<float>::max();
            values[5] = std::numeric_limits<float>::denorm_min();
        } else {
            values[1] = std::numeric_limits<T>::max();
        }
    });
    return volume;
}

template <class F>
std::string errorOf(F&& f) {
    try {
        f();
    } catch (const vri::Error& e) {
        return e.what();
    }
    FAIL("expected a vri::Error");
    return {};
}

void checkMentions(const std::string& message, std::initializer_list<std::string> parts) {
    INFO(message);
    CHECK(message.find('\n') == std::string::npos);
    for (const std::string& part : parts) CHECK_MESSAGE(message.find(part) != std::string::npos, part);
}

constexpr vri::VoxelType kAllTypes[] = {vri::VoxelType::UInt8, vri::VoxelType::UInt16, vri::VoxelType::Float32};

}  // namespace

TEST_CASE("volume io: raw round trip is exact for every type and byte order") {
    TempDir dir;
    for (vri::VoxelType type : kAllTypes)
        for (vri::ByteOrder order : {vri::ByteOrder::Little, vri::ByteOrder::Big}) {
            CAPTURE(vri::voxelTypeName(type));
            CAPTURE(static_cast<int>(order));
            vri::Volume volume = testVolume({5, 4, 3}, type);
            volume.spacing = {0.5, 1.0, 2.0};
            const fs::path path = dir / "v.raw";
            vri::writeRaw(path, volume, order);
            CHECK(fs::file_size(path) == volume.byteCount());
            const vri::Volume back = vri::readRaw(path, {volume.dims, type, order, volume.spacing});
            CHECK(back == volume);
        }
}

TEST_CASE("volume io: raw byte order is the one asked for on disk") {
    TempDir dir;
    vri::Volume volume({1, 1, 1}, vri::VoxelType::UInt16);
    volume.data<std::uint16_t>()[0] = 0x1234;
    vri::writeRaw(dir / "big.raw", volume, vri::ByteOrder::Big);
    vri::writeRaw(dir / "little.raw", volume, vri::ByteOrder::Little);
    CHECK(readBytes(dir / "big.raw") == "\x12\x34");
    CHECK(readBytes(dir / "little.raw") == "\x34\x12");
}

TEST_CASE("volume io: raw header bytes are skipped") {
    TempDir dir;
    writeBytes(dir / "h.raw", std::string("HEADER") + "\x01\x02\x03\x04");
    vri::RawLayout layout{{2, 2, 1}, vri::VoxelType::UInt8};
    layout.headerBytes = 6;
    const vri::Volume volume = vri::readRaw(dir / "h.raw", layout);
    CHECK(volume.value(1, 1, 0) == 4);
}

TEST_CASE("volume io: a raw file of the wrong size names the file, both sizes and the layout") {
    TempDir dir;
    const fs::path path = dir / "short.raw";
    writeBytes(path, std::string(24, '\0'));
    checkMentions(errorOf([&] { vri::readRaw(path, {{4, 3, 3}, vri::VoxelType::UInt8}); }),
                  {path.string() + ":", "24 bytes", "expected 36", "4x3x3 uint8"});
    checkMentions(errorOf([&] { vri::readRaw(path, {{4, 3, 2}, vri::VoxelType::UInt16}); }),
                  {path.string() + ":", "24", "48", "4x3x2 uint16"});
}

TEST_CASE("volume io: layout from Open SciVis file names") {
    const auto bonsai = vri::layoutFromFileName("/data/bonsai_256x256x256_uint8.raw");
    REQUIRE(bonsai);
    CHECK(bonsai->dims == glm::ivec3(256, 256, 256));
    CHECK(bonsai->type == vri::VoxelType::UInt8);
    CHECK(bonsai->order == vri::ByteOrder::Little);

    const auto teapot = vri::layoutFromFileName("boston_teapot_256x256x178_uint8.raw");
    REQUIRE(teapot);
    CHECK(teapot->dims == glm::ivec3(256, 256, 178));

    const auto field = vri::layoutFromFileName("field_3x4x5_float32.raw");
    REQUIRE(field);
    CHECK(field->type == vri::VoxelType::Float32);
    CHECK(vri::layoutFromFileName("x_10x20x30_uint16.raw")->type == vri::VoxelType::UInt16);

    CHECK_FALSE(vri::layoutFromFileName("boron.raw"));
    CHECK_FALSE(vri::layoutFromFileName("slice_256x256_uint8.raw"));
    CHECK_FALSE(vri::layoutFromFileName("a_0x2x2_uint8.raw"));
    CHECK_FALSE(vri::layoutFromFileName("a_2x2x2x2_uint8.raw"));
    checkMentions(errorOf([] { vri::layoutFromFileName("magnetic_512x512x512_float64.raw"); }),
                  {"magnetic_512x512x512_float64.raw", "float64"});
}

TEST_CASE("volume io: readVolume reads named raw files and asks for dims and type otherwise") {
    TempDir dir;
    const vri::Volume volume = testVolume({4, 3, 2}, vri::VoxelType::UInt16);
    vri::writeRaw(dir / "v_4x3x2_uint16.raw", volume);
    CHECK(vri::readVolume(dir / "v_4x3x2_uint16.raw") == volume);

    vri::writeRaw(dir / "anonymous.raw", volume);
    checkMentions(errorOf([&] { vri::readVolume(dir / "anonymous.raw"); }),
                  {(dir / "anonymous.raw").string() + ":", "--dims"});
    CHECK(vri::readVolume(dir / "anonymous.raw", vri::RawLayout{{4, 3, 2}, vri::VoxelType::UInt16}) == volume);
}

TEST_CASE("volume io: a missing file is named") {
    TempDir dir;
    for (const char* name : {"nope.raw", "nope.nhdr", "nope.dat", "nope.vdb", "nope_2x2x2_uint8.raw"}) {
        const fs::path path = dir / name;
        CHECK(errorOf([&] { vri::readVolume(path); }) == path.string() + ": no such file");
    }
    CHECK(errorOf([&] { vri::readVdb(dir / "nope.vdb"); }) == (dir / "nope.vdb").string() + ": no such file");
}

TEST_CASE("volume io: VDB round trip is exact") {
    TempDir dir;
    for (vri::VoxelType type : kAllTypes) {
        CAPTURE(vri::voxelTypeName(type));
        // Not a multiple of the 8^3 leaf size, with a constant block that OpenVDB keeps as a tile
        // and empty slabs at the far end that only the recorded dims bring back.
        vri::Volume volume = testVolume({21, 17, 30}, type);
        for (int z = 8; z < 16; ++z)
            for (int y = 8; y < 16; ++y)
                for (int x = 8; x < 16; ++x)
                    vri::dispatchVoxelType(type, [&](auto t) { volume.data<decltype(t)>()[volume.index(x, y, z)] = 7; });
        for (int z = 26; z < 30; ++z)
            for (int y = 0; y < 17; ++y)
                for (int x = 0; x < 21; ++x)
                    vri::dispatchVoxelType(type, [&](auto t) { volume.data<decltype(t)>()[volume.index(x, y, z)] = 0; });
        // The file holds the first voxel's centre, origin + spacing / 2: exact here, so the origin comes
        // back bit for bit (otherwise to within the rounding of that sum). 2/3 checks that the spacing is
        // kept exactly even where a translation is added to it.
        volume.spacing = {0.5, 0.75, 2.0 / 3.0};
        volume.origin = {-1.25, 3.0, -1.0 / 3.0};
        volume.range = vri::ValueRange{0.1, 1234.5};

        const fs::path path = dir / "v.vdb";
        vri::writeVdb(path, volume);
        vri::Volume back = vri::readVdb(path);
        CHECK(back.dims == volume.dims);
        CHECK(back.type == volume.type);
        CHECK(back.spacing == volume.spacing);
        CHECK(back.origin == volume.origin);
        CHECK(back.range == volume.range);
        CHECK(back.bytes == volume.bytes);
        CHECK(vri::readVolume(path) == volume);

        volume.range.reset();
        vri::writeVolume(path, volume);
        back = vri::readVolume(path);
        CHECK_FALSE(back.range);
        CHECK(back == volume);
    }
}

TEST_CASE("volume io: VDB stores empty space sparsely") {
    TempDir dir;
    vri::Volume volume({128, 128, 128}, vri::VoxelType::Float32);  // 8 MiB dense
    volume.data<float>()[volume.index(100, 3, 64)] = 1.5f;
    vri::writeVdb(dir / "sparse.vdb", volume);
    CHECK(fs::file_size(dir / "sparse.vdb") < 16 * 1024);
    CHECK(vri::readVdb(dir / "sparse.vdb") == volume);

    const vri::Volume empty({3, 2, 1}, vri::VoxelType::UInt8);
    vri::writeVdb(dir / "empty.vdb", empty);
    CHECK(vri::readVdb(dir / "empty.vdb") == empty);
}

TEST_CASE("volume io: VDB files from other programs are read over their active voxels") {
    // Without vri's metadata the reader falls back to the active bounding box and float32.
    // Renaming the metadata in place (same length, metadata are stored uncompressed) makes a
    // vri file look foreign without linking OpenVDB into the tests.
    TempDir dir;
    vri::Volume volume({10, 9, 8}, vri::VoxelType::UInt16);
    volume.spacing = {0.5, 2.0, 1.0};
    volume.origin = {1.0, 2.0, 3.0};
    for (int z = 3; z <= 4; ++z)
        for (int y = 2; y <= 6; ++y)
            for (int x = 1; x <= 3; ++x) volume.data<std::uint16_t>()[volume.index(x, y, z)] = 1000 * z + 10 * y + x;
    vri::writeVdb(dir / "v.vdb", volume);
    std::string bytes = readBytes(dir / "v.vdb");
    for (const std::string key : {"vri_dims", "vri_voxel_type"}) {
        const std::size_t at = bytes.find(key);
        REQUIRE(at != std::string::npos);
        bytes[at] = 'x';
    }
    writeBytes(dir / "foreign.vdb", bytes);

    for (const vri::Volume& foreign : {vri::readVdb(dir / "foreign.vdb"), vri::readVdb(dir / "foreign.vdb", "density")}) {
        CHECK(foreign.type == vri::VoxelType::Float32);
        CHECK(foreign.dims == glm::ivec3(3, 5, 2));
        CHECK(foreign.spacing == volume.spacing);
        CHECK(foreign.origin == glm::dvec3(1.0 + 1 * 0.5, 2.0 + 2 * 2.0, 3.0 + 3 * 1.0));
        CHECK(foreign.value(0, 0, 0) == 3021);
        CHECK(foreign.value(2, 4, 1) == 4063);
    }
}

TEST_CASE("volume io: VDB errors name the file") {
    TempDir dir;
    writeBytes(dir / "junk.vdb", "this is not a vdb file");
    checkMentions(errorOf([&] { vri::readVdb(dir / "junk.vdb"); }), {(dir / "junk.vdb").string() + ":"});

    vri::writeVdb(dir / "v.vdb", testVolume({2, 2, 2}, vri::VoxelType::UInt8));
    checkMentions(errorOf([&] { vri::readVdb(dir / "v.vdb", std::string("temperature")); }),
                  {(dir / "v.vdb").string() + ":", "temperature", "density"});
}

TEST_CASE("volume io: a .vdb cut short anywhere is refused with one message naming where its bytes end") {
    TempDir dir;
    vri::writeVolume(dir / "v.vdb", testVolume({20, 12, 9}, vri::VoxelType::Float32));
    const std::string whole = readBytes(dir / "v.vdb");
    for (const std::size_t keep : {std::size_t(4), std::size_t(30), std::size_t(70), std::size_t(130),
                                   whole.size() / 2, whole.size() - 1}) {
        CAPTURE(keep);
        writeBytes(dir / "cut.vdb", whole.substr(0, keep));
        const std::string path = (dir / "cut.vdb").string();
        const std::string message = errorOf([&] { vri::readVolume(path); });
        // The same message every time: it comes from the file's length, not from what OpenVDB reads past it.
        CHECK(errorOf([&] { vri::readVolume(path); }) == message);
        if (keep < 8) {
            CHECK(message == path + ": not a VDB file (its first 8 bytes are not OpenVDB's magic number)");
            continue;
        }
        checkMentions(message, {path + ": cut short: ", "beyond the file's end (" + std::to_string(keep) + " bytes)"});
    }
    checkMentions(errorOf([&] {
                      writeBytes(dir / "cut.vdb", whole.substr(0, whole.size() / 2));
                      vri::readVolume(dir / "cut.vdb");
                  }),
                  {"grid 0 ends at byte " + std::to_string(whole.size())});
}

TEST_CASE("volume io: NRRD .nhdr write and read round trip") {
    TempDir dir;
    for (vri::VoxelType type : kAllTypes) {
        CAPTURE(vri::voxelTypeName(type));
        vri::Volume volume = testVolume({6, 5, 4}, type);
        volume.spacing = {0.1, 0.2, 0.3};
        volume.origin = {1.0 / 3.0, -2.0, 0.0};
        volume.range = vri::ValueRange{-1.0, 2.0};
        vri::writeVolume(dir / "v.nhdr", volume);
        CHECK(fs::exists(dir / "v.raw"));
        CHECK(vri::readVolume(dir / "v.nhdr") == volume);
    }
}

TEST_CASE("volume io: NRRD headers from other programs") {
    TempDir dir;
    // 2x2x1 uint16, big endian, after 3 junk bytes.
    writeBytes(dir / "data.bin", std::string("abc") + std::string("\x00\x01\x00\x02\x01\x00\xff\xff", 8));
    writeBytes(dir / "big.nhdr", "NRRD0005\n"
                                 "# a comment\n"
                                 "content: test\n"
                                 "type: unsigned short int\n"
                                 "dimension: 3\n"
                                 "sizes: 2 2 1\n"
                                 "spacings: 0.5 0.25 4\n"
                                 "kinds: domain domain domain\n"
                                 "endian: big\n"
                                 "encoding: raw\n"
                                 "byte skip: 3\n"
                                 "datafile: data.bin\n"
                                 "units:=mm\n");
    const vri::Volume big = vri::readVolume(dir / "big.nhdr");
    CHECK(big.type == vri::VoxelType::UInt16);
    CHECK(big.dims == glm::ivec3(2, 2, 1));
    CHECK(big.spacing == glm::dvec3(0.5, 0.25, 4.0));
    CHECK(big.value(0, 0, 0) == 1);
    CHECK(big.value(1, 0, 0) == 2);
    CHECK(big.value(0, 1, 0) == 256);
    CHECK(big.value(1, 1, 0) == 65535);
    CHECK_FALSE(big.range);

    // Attached data after the blank line, space directions and origin.
    writeBytes(dir / "attached.nrrd", std::string("NRRD0004\r\n"
                                                  "type: uchar\n"
                                                  "dimension: 3\n"
                                                  "space: right-anterior-superior\n"
                                                  "sizes: 1 2 3\n"
                                                  "space directions: (2,0,0) (0,3,0) (0,0,4)\n"
                                                  "space origin: (10,20,30)\n"
                                                  "encoding: raw\n"
                                                  "\n") +
                                          "\x01\x02\x03\x04\x05\x06");
    const vri::Volume attached = vri::readVolume(dir / "attached.nrrd");
    CHECK(attached.dims == glm::ivec3(1, 2, 3));
    CHECK(attached.spacing == glm::dvec3(2, 3, 4));
    // The space origin is the first sample's centre; without "centers" the samples are cells, so the box
    // starts half a spacing before it.
    CHECK(attached.origin == glm::dvec3(9, 18.5, 28));
    CHECK(attached.value(0, 1, 2) == 6);

    // A node axis starts on its first sample.
    std::string text = readBytes(dir / "attached.nrrd");
    text.insert(text.find("encoding"), "centers: node cell ???\n");
    writeBytes(dir / "centred.nrrd", text);
    CHECK(vri::readVolume(dir / "centred.nrrd").origin == glm::dvec3(10, 18.5, 28));
}

TEST_CASE("volume io: gzip NRRD reads back every kept type in either byte order, and a converted one") {
    TempDir dir;
    const auto deflated = [](const std::string& bytes) {
        std::string packed(compressBound(bytes.size()), '\0');
        uLongf size = packed.size();
        REQUIRE(compress(reinterpret_cast<Bytef*>(packed.data()), &size,
                         reinterpret_cast<const Bytef*>(bytes.data()), bytes.size()) == Z_OK);
        packed.resize(size);
        return packed;
    };
    for (const vri::VoxelType type : kAllTypes)
        for (const char* endian : {"little", "big"}) {
            CAPTURE(vri::voxelTypeName(type));
            CAPTURE(endian);
            // 40^3 voxels: more than one of the reader's steps of growth for 16- and 32-bit voxels.
            const vri::Volume volume = testVolume({40, 40, 40}, type);
            std::string bytes(reinterpret_cast<const char*>(volume.bytes.data()), volume.bytes.size());
            const std::size_t voxel = vri::voxelSize(type);
            if (std::string(endian) == "big")
                for (std::size_t i = 0; i < bytes.size(); i += voxel) std::reverse(&bytes[i], &bytes[i] + voxel);
            const std::string name = type == vri::VoxelType::UInt8    ? "uchar"
                                     : type == vri::VoxelType::UInt16 ? "ushort"
                                                                      : "float";
            writeBytes(dir / "v.nrrd", "NRRD0004\ntype: " + name + "\ndimension: 3\nsizes: 40 40 40\nendian: " +
                                           endian + "\nencoding: gzip\n\n" + deflated(bytes));
            const vri::Volume read = vri::readVolume(dir / "v.nrrd");
            CHECK(read.type == type);
            CHECK(read.bytes == volume.bytes);
        }
    writeBytes(dir / "v.nrrd", "NRRD0004\ntype: short\ndimension: 3\nsizes: 2 1 1\nendian: big\nencoding: gzip\n\n" +
                                   deflated(std::string("\xfc\x18\x0b\xb8", 4)));
    const vri::Volume int16 = vri::readVolume(dir / "v.nrrd");
    CHECK(int16.type == vri::VoxelType::Float32);
    CHECK(int16.value(0, 0, 0) == -1000);
    CHECK(int16.value(1, 0, 0) == 3000);
}

TEST_CASE("volume io: NRRD types beyond uint8, uint16 and float32 become float32 by the stated rule") {
    TempDir dir;
    const auto read = [&](const std::string& type, const std::string& bytes, const std::string& extra = "") {
        writeBytes(dir / "v.raw", bytes);
        writeBytes(dir / "v.nhdr", "NRRD0004\ntype: " + type + "\ndimension: 3\nsizes: 2 1 1\nencoding: raw\n"
                                   "endian: little\ndata file: v.raw\n" + extra);
        return vri::readVolume(dir / "v.nhdr");
    };
    const vri::Volume int8 = read("signed char", std::string("\x80\x7f", 2));
    CHECK(int8.type == vri::VoxelType::Float32);
    CHECK(int8.value(0, 0, 0) == -128);
    CHECK(int8.value(1, 0, 0) == 127);
    CHECK(int8.range == vri::ValueRange{-128, 127});  // the stored type's full range, as for uint8
    const vri::Volume int16 = read("short", std::string("\x18\xfc\xb8\x0b", 4), "vri_range:=-1000 3000\n");
    CHECK(int16.value(0, 0, 0) == -1000);
    CHECK(int16.value(1, 0, 0) == 3000);
    CHECK(int16.range == vri::ValueRange{-1000, 3000});  // the file's range wins
    // A range whose width overflows a double would map every value to 0.
    checkMentions(errorOf([&] { read("short", std::string(4, '\0'), "vri_range:=-1e308 1e308\n"); }),
                  {"v.nhdr", "value range -1e+308 1e+308", "finite hi - lo"});
    CHECK(vri::parseRange("-1e307,1e307", "--range") == glm::dvec2(-1e307, 1e307));
    CHECK_THROWS_WITH_AS(vri::parseRange("-1e308,1e308", "--range"),
                         "--range: hi - lo must be at most the largest double (about 1.8e308), got '-1e308,1e308'",
                         vri::Error);
    const vri::Volume uint32 = read("uint", std::string("\x01\x00\x00\x01\xff\xff\xff\xff", 8));
    CHECK(uint32.value(0, 0, 0) == 16777217.0f);  // rounded to the nearest float: 2^24 + 1 is not one
    CHECK(uint32.value(0, 0, 0) == 16777216.0);
    CHECK(uint32.value(1, 0, 0) == 4294967296.0);
    CHECK(uint32.range == vri::ValueRange{0, 4294967295.0});
    double d[2] = {0.1, -2.5};
    const vri::Volume float64 = read("double", std::string(reinterpret_cast<const char*>(d), 16));
    CHECK(float64.value(0, 0, 0) == double(0.1f));
    CHECK(float64.value(1, 0, 0) == -2.5);
    CHECK_FALSE(float64.range);  // min..max, as for float32
    d[1] = 1e300;
    checkMentions(errorOf([&] { read("double", std::string(reinterpret_cast<const char*>(d), 16)); }),
                  {"v.raw", "voxel 1", "beyond float32's range"});
}

TEST_CASE("volume io: vri's NRRD files say where their samples are") {
    TempDir dir;
    vri::Volume volume = testVolume({3, 2, 2}, vri::VoxelType::UInt16);
    volume.spacing = {0.5, 2, 0.25};
    volume.origin = {-1, 4, 8};
    for (const char* name : {"v.nhdr", "v.nrrd"}) {
        CAPTURE(name);
        vri::writeVolume(dir / name, volume);
        const std::string text = readBytes(dir / name);
        CHECK(text.find("centers: cell cell cell\n") != std::string::npos);
        CHECK(text.find("space origin: (-0.75,5,8.125)\n") != std::string::npos);
        CHECK(vri::readVolume(dir / name) == volume);
    }
    CHECK(readBytes(dir / "v.nrrd").find("data file") == std::string::npos);  // attached
    CHECK(vri::filesWrittenBy(dir / "v.nrrd") == std::vector<fs::path>{dir / "v.nrrd"});
}

TEST_CASE("volume io: bad NRRD headers name the file and the field") {
    TempDir dir;
    writeBytes(dir / "v.raw", std::string(8, '\1'));
    const auto header = [&](const std::string& type, const std::string& encoding, const std::string& extra) {
        writeBytes(dir / "v.nhdr", "NRRD0004\ntype: " + type + "\ndimension: 3\nsizes: 2 2 2\nencoding: " + encoding +
                                       "\nendian: little\ndata file: v.raw\n" + extra);
        return (dir / "v.nhdr").string();
    };
    std::string path = header("uchar", "raw", "");
    CHECK(vri::readVolume(path).value(1, 1, 1) == 1);

    path = header("uchar", "ascii", "");
    checkMentions(errorOf([&] { vri::readVolume(path); }), {path + ":", "encoding", "ascii"});
    path = header("uchar", "gzip", "");  // v.raw is not deflated
    checkMentions(errorOf([&] { vri::readVolume(path); }), {path + ":", "v.raw", "gzip"});
    path = header("uchar", "gzip", "byte skip: 2\n");
    checkMentions(errorOf([&] { vri::readVolume(path); }), {path + ":", "byte skip", "gzip"});
    path = header("int64", "raw", "");
    checkMentions(errorOf([&] { vri::readVolume(path); }), {path + ":", "type", "int64"});
    path = header("uchar", "raw", "centers: cell cell\n");
    checkMentions(errorOf([&] { vri::readVolume(path); }), {path + ":", "centers", "expected 3"});
    path = header("uchar", "raw", "centers: cell middle cell\n");
    checkMentions(errorOf([&] { vri::readVolume(path); }), {path + ":", "centers", "middle"});
    path = header("uchar", "raw", "space directions: (1,0.5,0) (0,1,0) (0,0,1)\n");
    checkMentions(errorOf([&] { vri::readVolume(path); }), {path + ":", "space directions"});
    path = header("uint16", "raw", "");
    checkMentions(errorOf([&] { vri::readVolume(path); }), {path + ":", "v.raw", "8 bytes", "expected 16"});

    writeBytes(dir / "four.nhdr", "NRRD0004\ntype: uchar\ndimension: 4\nsizes: 1 2 2 2\nencoding: raw\n");
    checkMentions(errorOf([&] { vri::readVolume(dir / "four.nhdr"); }), {(dir / "four.nhdr").string() + ":", "dimension"});
    writeBytes(dir / "magic.nhdr", "P5\n2 2\n");
    checkMentions(errorOf([&] { vri::readVolume(dir / "magic.nhdr"); }), {(dir / "magic.nhdr").string() + ":", "NRRD"});
}

namespace {

// boron.dat's key set over a 3x4x5 uint16 volume whose voxel (x,y,z) holds 100z + 10y + x.
void writeSmallBoron(const TempDir& dir, const std::string& format = "UINT16") {
    std::string raw;
    for (int z = 0; z < 5; ++z)
        for (int y = 0; y < 4; ++y)
            for (int x = 0; x < 3; ++x) {
                const int v = 100 * z + 10 * y + x;
                raw += static_cast<char>(v & 0xff);
                raw += static_cast<char>(v >> 8);
            }
    writeBytes(dir / "small.raw", raw);
    writeBytes(dir / "small.dat", "Rawfile: small.raw\n"
                                  "Resolution: 3 4 5\n"
                                  "Format: " + format + "\n"
                                  "DataRange: 0 65535\n"
                                  "ValueRange: 0.0 0.000098763573\n"
                                  "ValueUnit: e/Angstrom^3\n"
                                  "ValueName: Charge Density\n"
                                  "Wrapping: Repeat Repeat Repeat\n"
                                  "BasisVector1: 1.5 0.0 0.0\n"
                                  "basisvector2: 0.0 2.0 0.0\n"
                                  "BASISVECTOR3: 0.0 0.0 1.25\n"
                                  "AxisNames: x y z\n"
                                  "AxisUnits: Angstrom Angstrom Angstrom\n");
}

}  // namespace

TEST_CASE("volume io: Inviwo .dat read") {
    TempDir dir;
    writeSmallBoron(dir);
    const vri::Volume volume = vri::readVolume(dir / "small.dat");
    CHECK(volume.dims == glm::ivec3(3, 4, 5));
    CHECK(volume.type == vri::VoxelType::UInt16);
    CHECK(volume.spacing == glm::dvec3(0.5, 0.5, 0.25));
    CHECK(volume.origin == glm::dvec3(0, 0, 0));
    REQUIRE(volume.range);
    CHECK(*volume.range == vri::ValueRange{0, 65535});
    CHECK(volume.value(2, 3, 4) == 432);
    CHECK(volume.value(1, 0, 3) == 301);
}

TEST_CASE("volume io: Inviwo .dat write and read round trip") {
    TempDir dir;
    vri::Volume volume = testVolume({4, 2, 3}, vri::VoxelType::Float32);
    volume.spacing = {0.5, 0.25, 2.0};
    volume.origin = {-1.0, 0.5, 8.0};
    volume.range = vri::ValueRange{-3.0, 7.5};
    vri::writeVolume(dir / "v.dat", volume);
    CHECK(vri::readVolume(dir / "v.dat") == volume);
}

TEST_CASE("volume io: bad .dat files name the file and the key") {
    TempDir dir;
    writeSmallBoron(dir, "INT16");
    const std::string path = (dir / "small.dat").string();
    checkMentions(errorOf([&] { vri::readVolume(path); }), {path + ":3:", "Format", "INT16"});

    writeBytes(dir / "norawfile.dat", "Resolution: 3 4 5\nFormat: UINT16\n");
    checkMentions(errorOf([&] { vri::readVolume(dir / "norawfile.dat"); }),
                  {(dir / "norawfile.dat").string() + ":", "Rawfile"});

    writeBytes(dir / "wrongsize.dat", "Rawfile: small.raw\nResolution: 3 4 6\nFormat: UINT16\n");
    checkMentions(errorOf([&] { vri::readVolume(dir / "wrongsize.dat"); }),
                  {(dir / "wrongsize.dat").string() + ":", "small.raw", "120 bytes", "expected 144"});
}

TEST_CASE("volume io: a float volume holding NaN or infinity is refused in every format, naming the voxel") {
    TempDir dir;
    for (const float bad : {std::numeric_limits<float>::quiet_NaN(), -std::numeric_limits<float>::infinity()}) {
        vri::Volume volume({3, 2, 2}, vri::VoxelType::Float32);
        volume.data<float>()[1] = 5.0f;
        volume.data<float>()[10] = bad;  // x 1, y 1, z 1
        for (const std::string name : {"v_3x2x2_float32.raw", "v.nhdr", "v.dat", "v.vdb"}) {
            CAPTURE(name);
            vri::writeVolume(dir / name, volume);
            checkMentions(errorOf([&] { vri::readVolume(dir / name); }),
                          {(dir / name).string() + ": voxel 10 (x 1, y 1, z 1) is " + vri::exactNumber(bad),
                           "finite values"});
        }
    }
}

TEST_CASE("volume io: ranges, spacings, byte offsets and boxes out of range are refused with file and line") {
    TempDir dir;
    writeSmallBoron(dir);
    const auto datFile = [&](const std::string& extra) {
        writeBytes(dir / "x.dat", "Rawfile: small.raw\nResolution: 3 4 5\nFormat: UINT16\n" + extra);
        return dir / "x.dat";
    };
    const auto dat = [&](const std::string& extra) { return errorOf([&] { vri::readVolume(datFile(extra)); }); };
    const std::string x = (dir / "x.dat").string();
    checkMentions(dat("DataRange: 5 5\n"), {x + ":4: DataRange: expected lo < hi, got '5 5'"});
    checkMentions(dat("DataRange: 255 0\n"), {x + ":4: DataRange: expected lo < hi, got '255 0'"});
    checkMentions(dat("DataRange: 0 inf\n"), {x + ":4: DataRange", "not a finite number"});
    checkMentions(dat("ByteOffset: 1e30\n"), {x + ":4: ByteOffset: expected a byte count", "'1e30'"});
    checkMentions(dat("ByteOffset: -2\n"), {x + ":4: ByteOffset: expected a byte count"});
    checkMentions(dat("ByteOffset: 99999999999999999999999\n"), {x + ":4: ByteOffset", "is too large"});
    checkMentions(dat("ByteOffset: 18446744073709551615\n"), {x + ":", "header of", "too large"});
    checkMentions(dat("Offset: 1e308 0 0\nBasisVector1: 1e308 0 0\nBasisVector2: 0 1 0\nBasisVector3: 0 0 1\n"),
                  {x + ": the box", "along x", "beyond the range of a double"});
    CHECK(vri::readVolume(datFile("DataRange: 0 1000\nByteOffset: 0\n")).range == vri::ValueRange{0, 1000});

    writeBytes(dir / "v.raw", std::string(8, '\1'));
    const auto nhdrFile = [&](const std::string& extra) {
        writeBytes(dir / "v.nhdr", "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n"
                                   "data file: v.raw\n" + extra);
        return dir / "v.nhdr";
    };
    const auto nhdr = [&](const std::string& extra) { return errorOf([&] { vri::readVolume(nhdrFile(extra)); }); };
    const std::string v = (dir / "v.nhdr").string();
    checkMentions(nhdr("spacings: 1 1e308 1\n"), {v + ":7: spacings: spacing 1e+308 along y", "times 2 voxels"});
    checkMentions(nhdr("spacings: 1 0 1\n"), {v + ":7: spacings: spacing 0 along y must be positive"});
    checkMentions(nhdr("spacings: -1 1 1\n"), {v + ":7: spacings: spacing -1 along x"});
    checkMentions(nhdr("spacings: 1 nan 1\n"), {v + ":7: spacings", "not a finite number"});
    checkMentions(nhdr("space directions: (1e308,0,0) (0,1,0) (0,0,1)\n"),
                  {v + ":7: space directions: spacing 1e+308 along x"});
    checkMentions(nhdr("vri_range:=3 3\n"), {v + ":7: vri_range: expected lo < hi"});
    checkMentions(nhdr("byte skip: 1e3\n"), {v + ":7: byte skip: expected a byte count", "'1e3'"});
    checkMentions(nhdr("byte skip: -2\n"), {v + ":7: byte skip: expected a byte count"});
    CHECK(vri::readVolume(nhdrFile("byte skip: -1\nspacings: 1e300 1 1\n")).spacing.x == 1e300);
    CHECK(vri::readVolume(nhdrFile("byte skip: 0\n")).value(1, 1, 1) == 1);
}

TEST_CASE("volume io: writeVolume refuses unknown extensions and writes nothing") {
    TempDir dir;
    const vri::Volume volume({2, 2, 2}, vri::VoxelType::UInt8);
    checkMentions(errorOf([&] { vri::writeVolume(dir / "v.png", volume); }), {(dir / "v.png").string() + ":"});
    CHECK(fs::is_empty(dir.path));
}

TEST_CASE("volume io: the files a write creates") {
    CHECK(vri::filesWrittenBy("out/v.vdb") == std::vector<fs::path>{"out/v.vdb"});
    CHECK(vri::filesWrittenBy("out/v.nhdr") == std::vector<fs::path>{"out/v.raw", "out/v.nhdr"});
    CHECK(vri::filesWrittenBy("v.DAT") == std::vector<fs::path>{"v.raw", "v.DAT"});
}

TEST_CASE("volume io: the Inviwo boron data set, when present") {
    const char* env = std::getenv("VRI_DATA_DIR");
    const fs::path path = fs::path(env ? env : "/work/shared/data/volumes") / "boron.dat";
    if (!fs::exists(path)) return;  // CI without the data sets
    const vri::Volume boron = vri::readVolume(path);
    CHECK(boron.dims == glm::ivec3(150, 150, 150));
    CHECK(boron.type == vri::VoxelType::UInt16);
    REQUIRE(boron.range);
    CHECK(*boron.range == vri::ValueRange{0, 65535});
    CHECK(boron.spacing.x == doctest::Approx(5.05970000847 / 150));
    CHECK(boron.spacing.y == doctest::Approx(5.63039999861 / 150));
    CHECK(boron.spacing.z == doctest::Approx(6.98849999885 / 150));
}

TEST_CASE("volume io: VDB dims metadata are checked against the active voxels and the file before allocating") {
    // vri_dims is stored uncompressed: "vri_dims", its type name "vec3i" and size 12, then x, y, z.
    TempDir dir;
    vri::Volume volume({4, 3, 2}, vri::VoxelType::UInt8);
    for (std::size_t i = 0; i < volume.bytes.size(); ++i) volume.bytes[i] = std::byte(i + 1);
    vri::writeVdb(dir / "v.vdb", volume);
    const std::string bytes = readBytes(dir / "v.vdb");
    const std::size_t dimsAt = bytes.find("vri_dims");
    REQUIRE(dimsAt != std::string::npos);
    const std::size_t valuesAt = dimsAt + 8 + 4 + 5 + 4;
    REQUIRE(bytes.compare(dimsAt + 12, 5, "vec3i") == 0);
    const auto forged = [&](std::int32_t x, std::int32_t y, std::int32_t z) {
        std::string copy = bytes;
        for (int axis = 0; axis < 3; ++axis) {
            const std::int32_t v = axis == 0 ? x : axis == 1 ? y : z;
            std::memcpy(&copy[valuesAt + 4 * axis], &v, 4);  // little-endian, as OpenVDB writes
        }
        writeBytes(dir / "forged.vdb", copy);
        return dir / "forged.vdb";
    };
    CHECK(vri::readVdb(forged(4, 3, 2)) == volume);
    // Trailing empty slabs are what vri_dims is for.
    CHECK(vri::readVdb(forged(4, 3, 5)).dims == glm::ivec3(4, 3, 5));
    // The file: the product wraps to 0 bytes in size_t.
    CHECK_THROWS_WITH_AS(vri::readVdb(forged(4194304, 4194304, 1048576)),
                         doctest::Contains("vri_dims 4194304x4194304x1048576 (uint8): needs about 1.84e+19 bytes"),
                         vri::Error);
    // 1 GiB claimed by a file of a few KB.
    CHECK_THROWS_WITH_AS(vri::readVdb(forged(1024, 1024, 1024)),
                         doctest::Contains("needs 1073741824 bytes, limit 268435456 for a file of"), vri::Error);
    CHECK_THROWS_WITH_AS(vri::readVdb(forged(2, 3, 2)), doctest::Contains("does not contain the active voxels"),
                         vri::Error);
}

TEST_CASE("volume io: a raw file's value range streams box by box and names a NaN by its place in the volume") {
    TempDir dir;
    // Whole rows of a plane a chunk (1000 x 1048 voxels, then the plane's last 452 rows), and rows longer than a
    // chunk taken in runs (2^20 voxels, then 5): the range is the whole volume's, a NaN named in either kind.
    for (const glm::ivec3 dims : {glm::ivec3(1000, 1500, 2), glm::ivec3((1 << 20) + 5, 1, 2)})
        for (vri::ByteOrder order : {vri::ByteOrder::Little, vri::ByteOrder::Big}) {
            CAPTURE(dims.x);
            vri::Volume volume(dims, vri::VoxelType::Float32);
            float* v = volume.data<float>();
            for (std::size_t i = 0; i < volume.voxelCount(); ++i) v[i] = static_cast<float>(i % 977) - 300.f;
            const glm::ivec3 low(dims.x - 1, dims.y - 1, 1), high(0, dims.y - 1, 1);  // both in a plane's last chunk
            v[volume.index(low.x, low.y, low.z)] = -1e6f;
            v[volume.index(high.x, high.y, high.z)] = 2e6f;
            const fs::path path = dir / "v.raw";
            vri::writeRaw(path, volume, order);
            const vri::RawLayout layout{dims, vri::VoxelType::Float32, order};
            const vri::ValueRange range = vri::rawValueRange(path, layout, "");
            CHECK(range.lo == -1e6);
            CHECK(range.hi == 2e6);
            v[volume.index(dims.x - 3, dims.y - 1, 1)] = std::numeric_limits<float>::quiet_NaN();
            vri::writeRaw(path, volume, order);
            const std::uint64_t index = volume.index(dims.x - 3, dims.y - 1, 1);
            checkMentions(errorOf([&] { vri::rawValueRange(path, layout, "the volume"); }),
                          {"the volume: voxel " + std::to_string(index) + " (x " + std::to_string(dims.x - 3) + ", y " +
                           std::to_string(dims.y - 1) + ", z 1) is nan"});
        }
}
