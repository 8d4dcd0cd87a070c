# Sourced by the tool tests: strict mode, an empty scratch directory to work in, and fail().
set -euo pipefail
rm -rf "$VRI_SCRATCH"
mkdir -p "$VRI_SCRATCH"
cd "$VRI_SCRATCH"

fail() { echo "FAIL: $*" >&2; exit 1; }
