#pragma once
// What a result's manifest records about how it was made: the machine, the build, the exact
// command and when. Include <nlohmann/json.hpp> where the results are used.
#include <string>
#include <string_view>

#include <nlohmann/json_fwd.hpp>

namespace vri {

// {"cpu_model", "logical_cores", "usable_cores" (this process's CPU affinity), "memory_bytes",
//  "os", "kernel", "hostname"}; a field that cannot be found reads "unknown" (or 0).
nlohmann::json machineInfo();

// {"vri_version", "git_commit" (the commit built from, read at build time, "+modified"
//  when tracked files differed from it), "build_type" (CMAKE_BUILD_TYPE), "compiler",
//  "openexr", "libpng", "openimageio", "openvdb", "tbb"}.
nlohmann::json buildInfo();

// {"argv": [...], "shell": a command line that a POSIX shell reads back into the same argv and engine
// environment, "environment": the engine_environment.h variables set, when any is}.
nlohmann::json commandLine(int argc, char** argv);

// `word` as one POSIX shell word, for a command line printed for a person to read or paste (vri
// never runs one through a shell): unchanged when it holds only characters no shell treats
// specially, else in single quotes.
std::string shellQuote(std::string_view word);

// Now, UTC, ISO 8601 to the second: "2025-01-31T23:59:59Z".
std::string utcTimestamp();
// This machine's host name (gethostname), "unknown" when it has none.
std::string hostName();

}  // namespace vri
