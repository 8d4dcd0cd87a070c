#pragma once
// The temporary files writeAtomically writes through, by name: ".STEM.tmp.PID.EXT" beside the target
// (STEM and EXT the target's, PID the writer's; for a target name of more than 239 bytes, STEM is cut and
// ends in "~" and 16 hex digits of the name's SHA-512, so that the name stays within 255 bytes). A process ended by kill -9 or a power cut leaves its
// file there (a SIGINT, SIGTERM or SIGHUP removes it: atomic_file.cpp); its pid tells whether the
// writer may still be at work.
#include <sys/types.h>

#include <filesystem>
#include <vector>

namespace vri {

// The temporary file process `pid` writes `target` through.
std::filesystem::path temporaryFileFor(const std::filesystem::path& target, pid_t pid);

// Removes the temporary files of `target` whose process is gone (kill(PID, 0) fails with ESRCH): regular
// files beside it named exactly temporaryFileFor(target, PID) for some PID. Only names a writer of that
// very target could have made are touched, so a user's ".notes.tmp.12.txt" stays unless notes.txt is the
// target; a live process's file, links and anything else are left alone. Returns the files removed.
std::vector<std::filesystem::path> removeStaleTempFiles(const std::filesystem::path& target);

}  // namespace vri
