// The dataset catalog: parsing, errors with positions, lookup and verification of a file.
#include <doctest/doctest.h>

#include <fstream>

#include "temp_dir.h"
#include "libvri/experiment/datasets.h"
#include "libvri/util/error.h"
#include "libvri/util/sha512.h"

using namespace vri;

namespace {

// An 2x2x1 uint8 raw file "abcd" and a catalog entry for it.
const std::string kTinyDigest = [] {
    const std::string bytes = "abcd";
    return sha512Hex(std::as_bytes(std::span(bytes.data(), bytes.size())));
}();

std::string tinyCatalog(const std::string& status = "exact", const std::string& digest = kTinyDigest) {
    return "datasets:\n"
           "  - name: tiny\n"
           "    file: tiny.raw\n"
           "    dims: [2, 2, 1]\n"
           "    type: uint8\n"
           "    spacing: [1, 0.75, 1]\n"
           "    sha512: " + digest + "\n"
           "    url: https://example.org/tiny.raw\n"
           "    status: " + status + "\n"
           "    note: four bytes\n";
}

}  // namespace

TEST_CASE("datasets: the project's catalog lists the papers' datasets") {
    const auto catalog = loadDatasetCatalog(std::filesystem::path(VRI_TEST_DATA_DIR).parent_path().parent_path() / "experiments" / "datasets.yaml");
    for (const char* name : {"bonsai", "blunt_fin", "boston_teapot", "engine", "boron", "fuel", "neghip", "hydrogen_atom"})
        CHECK_NOTHROW(findDataset(catalog, name, "test"));
    const DatasetInfo& boron = findDataset(catalog, "boron", "test");
    CHECK(boron.type == VoxelType::UInt16);
    CHECK(boron.status == "reconstructed");
    CHECK(datasetPath(boron, "/data") == std::filesystem::path("/data/boron.dat"));
    const DatasetInfo& fin = findDataset(catalog, "blunt_fin", "test");
    CHECK(fin.dims == glm::ivec3(256, 128, 64));
    CHECK(fin.spacing.y == 0.75);
    CHECK(datasetPath(fin, "/data") == std::filesystem::path("/data/blunt_fin_256x128x64_uint8.raw"));
    CHECK(rawLayout(fin).spacing == fin.spacing);
}

TEST_CASE("datasets: catalog errors point at file, line and column") {
    auto error = [](const std::string& text) {
        try {
            parseDatasetCatalog(text, "c.yaml");
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    CHECK(error(tinyCatalog()) == "no error");
    CHECK(error(tinyCatalog("maybe")) == "c.yaml:9:13: status 'maybe' is unknown (expected exact, reconstructed or stand-in)");
    CHECK(error(tinyCatalog("exact", "abc")) == "c.yaml:7:13: sha512 must be 128 lowercase hex digits");
    CHECK(error(tinyCatalog("exact", "''")) == "c.yaml:2:5: dataset 'tiny' is 'exact' but has no sha512 to prove it");
    CHECK(error(tinyCatalog("reconstructed", "''")) == "no error");
    CHECK(error("datasets:\n  - name: x\n    colour: red\n") ==
          "c.yaml:3:5: unknown key 'colour' (expected one of: name, file, dims, type, byte_order, spacing, header, "
          "header_url, sha512, url, status, note)");
    std::string badDims = tinyCatalog();
    badDims.replace(badDims.find("[2, 2, 1]"), 9, "[2, 0.5, 1]");
    CHECK(error(badDims) == "c.yaml:4:15: dims must be positive integers");
    std::string climbing = tinyCatalog();
    climbing.replace(climbing.find("tiny.raw"), 8, "../tiny.raw");
    CHECK(error(climbing) == "c.yaml:3:11: '../tiny.raw' must be a path relative to the data directory");
    CHECK(error(tinyCatalog() + tinyCatalog().substr(10)) == "c.yaml:11:11: dataset 'tiny' is listed twice");
    CHECK(error("datasets: [\n") .starts_with("c.yaml:2:1: malformed YAML"));
}

TEST_CASE("datasets: findDataset names the unknown dataset and the known ones") {
    const auto catalog = parseDatasetCatalog(tinyCatalog(), "c.yaml");
    CHECK_THROWS_WITH_AS(findDataset(catalog, "bonzai", "e.yaml:3:9"),
                         "e.yaml:3:9: unknown dataset 'bonzai' (known: tiny)", Error);
}

TEST_CASE("datasets: verify and check a tiny file") {
    test::TempDir dir("datasets");
    const DatasetInfo tiny = parseDatasetCatalog(tinyCatalog(), "c.yaml").front();
    std::string why;
    CHECK_FALSE(verifyDataset(tiny, dir.path, &why));
    CHECK(why.ends_with("tiny.raw: missing"));
    CHECK(checkDataset(tiny, dir.path, false).state == DatasetState::Missing);

    std::ofstream(dir / "tiny.raw") << "abcd";
    CHECK(verifyDataset(tiny, dir.path, &why));
    CHECK(why.empty());
    CHECK(checkDataset(tiny, dir.path, false).state == DatasetState::Verified);

    std::ofstream(dir / "tiny.raw") << "abce";
    CHECK_FALSE(verifyDataset(tiny, dir.path, &why));
    CHECK(why.find("SHA-512") != std::string::npos);
    CHECK(checkDataset(tiny, dir.path, false).state == DatasetState::Mismatch);
    // A reconstructed dataset's digest is ours, not a published one: reported, not held against it.
    const DatasetInfo rebuilt = parseDatasetCatalog(tinyCatalog("reconstructed"), "c.yaml").front();
    CHECK(checkDataset(rebuilt, dir.path, false).state == DatasetState::Ok);

    std::ofstream(dir / "tiny.raw") << "abc";
    CHECK_FALSE(verifyDataset(tiny, dir.path, &why));
    CHECK(why.ends_with("tiny.raw: 3 bytes, expected 4 for 2x2x1 uint8"));
    CHECK(checkDataset(rebuilt, dir.path, false).state == DatasetState::Mismatch);
}
