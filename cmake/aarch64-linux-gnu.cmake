# Cross build for 64-bit Arm Linux on a Debian amd64 host (scripts/check-neon): Debian's cross compiler
# (g++-aarch64-linux-gnu) and the target's libraries installed as multiarch packages (libhwy-dev:arm64,
# libtbb-dev:arm64), which put their CMake packages in /usr/lib/aarch64-linux-gnu/cmake and share /usr/include
# with the host's. The header-only packages (GLM, doctest, nlohmann-json) are architecture-independent.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
# Multiarch: find_package and find_library look in lib/aarch64-linux-gnu (and lib/, share/), never in the
# host's lib/x86_64-linux-gnu.
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)
