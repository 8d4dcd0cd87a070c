# Sourced by the tool tests: strict mode, an empty scratch directory to work in, and fail().
set -euo pipefail
rm -rf "$VRI_SCRATCH"
mkdir -p "$VRI_SCRATCH"
cd "$VRI_SCRATCH"

fail() { echo "FAIL: $*" >&2; exit 1; }

# True when the tools were built with the Vulkan backend (ctest sets VRI_VULKAN): a test's Vulkan cases
# run only then; in a -DVRI_VULKAN=OFF build `--backend vulkan` is an error of its own.
built_with_vulkan() { [ "${VRI_VULKAN:-ON}" = ON ]; }
