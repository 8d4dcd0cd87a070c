#include <doctest/doctest.h>

#include <nlohmann/json.hpp>
#include <cctype>
#include <regex>
#include <string>
#include <vector>

#include "scoped_environment.h"
#include "libvri/core/engine_environment.h"
#include "libvri/core/simd_target.h"
#include "libvri/io/provenance.h"

TEST_CASE("provenance: shell quoting leaves plain words alone and quotes the rest") {
    CHECK(vri::shellQuote("vri-render") == "vri-render");
    CHECK(vri::shellQuote("--fail=1e-6,0.5/x:y@z%") == "--fail=1e-6,0.5/x:y@z%");
    CHECK(vri::shellQuote("") == "''");
    CHECK(vri::shellQuote("two words") == "'two words'");
    CHECK(vri::shellQuote("$HOME*") == "'$HOME*'");
    CHECK(vri::shellQuote("it's") == "'it'\\''s'");
    // Words that a shell would read otherwise as a command's first word: an assignment, a job.
    CHECK(vri::shellQuote("build=x/bin/vri-render") == "'build=x/bin/vri-render'");
    CHECK(vri::shellQuote("_a1=2") == "'_a1=2'");
    CHECK(vri::shellQuote("%1") == "'%1'");
    CHECK(vri::shellQuote("1a=2") == "1a=2");
    CHECK(vri::shellQuote("a\nb") == "'a\nb'");
    CHECK(vri::shellQuote("$(touch x) `touch y`") == "'$(touch x) `touch y`'");
}

TEST_CASE("provenance: command line as argv and as a pasteable line") {
    std::vector<std::string> words{"vri-diff", "a b.exr", "it's.exr", "--json", "-"};
    std::vector<char*> argv;
    for (std::string& word : words) argv.push_back(word.data());
    // The engine's variables (engine_environment.h) as assignments before the command, and on their own;
    // an empty one is unset to its readers and left out; a target's name as its reader spells it.
    const vri::test::ScopedEnvironment target(vri::kSimdTargetVariable, std::nullopt);
    const vri::test::ScopedEnvironment loads(vri::kVoxelLoadsVariable, std::string());
    const nlohmann::json command = vri::commandLine(static_cast<int>(argv.size()), argv.data());
    CHECK(command["argv"] == nlohmann::json(words));
    CHECK(command["shell"] == "vri-diff 'a b.exr' 'it'\\''s.exr' --json -");
    CHECK(!command.contains("environment"));
    std::string best = vri::availableSimdTargets().front(), lower = best;  // "AVX3" here, "NEON" on Arm
    for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    target.set(lower);
    loads.set("gather;x");
    const nlohmann::json withEnvironment = vri::commandLine(static_cast<int>(argv.size()), argv.data());
    CHECK(withEnvironment["argv"] == nlohmann::json(words));
    CHECK(withEnvironment["shell"] ==
          "VRI_SIMD_TARGET=" + best + " VRI_VOXEL_LOADS='gather;x' vri-diff 'a b.exr' 'it'\\''s.exr' --json -");
    CHECK(withEnvironment["environment"] == nlohmann::json{{"VRI_SIMD_TARGET", best}, {"VRI_VOXEL_LOADS", "gather;x"}});
}

TEST_CASE("provenance: timestamp, machine and build") {
    CHECK(std::regex_match(vri::utcTimestamp(), std::regex(R"(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ)")));

    const nlohmann::json machine = vri::machineInfo();
    for (const char* key : {"cpu_model", "os", "kernel", "hostname"}) {
        CAPTURE(key);
        REQUIRE(machine.contains(key));
        CHECK(!machine[key].get<std::string>().empty());
    }
    CHECK(machine["logical_cores"].get<int>() >= 1);
    CHECK(machine["usable_cores"].get<int>() >= 1);
    CHECK(machine["memory_bytes"].get<std::uint64_t>() > 0);

    const nlohmann::json build = vri::buildInfo();
    for (const char* key : {"vri_version", "git_commit", "build_type", "compiler", "openexr", "libpng", "openimageio",
                            "openvdb", "tbb"}) {
        CAPTURE(key);
        REQUIRE(build.contains(key));
        CHECK(!build[key].get<std::string>().empty());
    }
}
