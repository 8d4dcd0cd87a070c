#pragma once
// Which Highway target the SIMD code runs on: the packet engine (simd_march.h) and the exact method's
// Gauss batches (exact_gauss_batch.h). By default Highway picks the best target this CPU and build have;
// a lower one can be asked for (`--simd AVX2`, or VRI_SIMD_TARGET=AVX2 for every render of a process)
// so that one host measures AVX2 beside AVX-512, and the scalar fallback beside both. Every target
// gives the same image bit for bit (tests/unit/simd_march_test.cpp, exact_reference_test.cpp).
#include <string>
#include <string_view>
#include <vector>

namespace vri {

// The targets this build compiled and this CPU runs, best first, by Highway's names ("AVX3", "AVX2",
// "SSE4", "SSSE3", "SCALAR", "NEON", ...).
std::vector<std::string> availableSimdTargets();
// The same, as one line for messages: "AVX3, AVX2, SSE4, SSSE3, SCALAR".
std::string simdTargetList();

// `name` (any case) as Highway spells it, when it is one of availableSimdTargets(); empty otherwise.
std::string simdTargetNamed(std::string_view name);

// The environment's choice: VRI_SIMD_TARGET as simdTargetNamed spells it, or empty when it is unset or
// empty; throws vri::Error naming the variable and the targets there are when it names none of them.
std::string simdTargetFromEnvironment();

// Makes `target` (simdTargetNamed's spelling; empty: the environment's choice, else the best) the
// one Highway dispatches to, until the next call. Process-wide (hwy::DisableTargets): call it before a
// frame's threads start, not while another frame runs.
void useSimdTarget(const std::string& target);

}  // namespace vri
