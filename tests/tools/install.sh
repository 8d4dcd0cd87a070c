#!/usr/bin/env bash
# The installed package, as a project outside vri's tree uses it: `cmake --install` of this build into a
# scratch prefix (no rebuild), then examples/render_linear_field configured with find_package(vri) against
# that prefix alone, built, run, and its image checked bit for bit against the installed vri-render's of
# the same scene; the same program built again through pkg-config's vri.pc; every installed header
# compiled together from the prefix, none of them naming OpenVDB, OpenImageIO or Vulkan; --version of
# every installed tool; and the Python module, where the build has one, imported from the prefix. Skipped (77) in a sanitizer build, whose libraries need the sanitizers' runtime.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"

cache="$VRI_BUILD/CMakeCache.txt"
cached() { sed -n "s/^$1:[A-Z]*=//p" "$cache"; }  # a value of the build's CMake cache
[ "$(cached VRI_SANITIZE)" = ON ] && { echo "sanitizer build: the example would need its runtime: skipping"; exit 77; }
cxx=$(cached CMAKE_CXX_COMPILER)
launcher=$(cached CMAKE_CXX_COMPILER_LAUNCHER)
prefix="$PWD/prefix"

cmake --install "$VRI_BUILD" --prefix "$prefix" > install.log 2>&1 || { cat install.log >&2; fail "cmake --install"; }
bin="$prefix/bin"
config=$(find "$prefix" -name vriConfig.cmake)
pc=$(find "$prefix" -name vri.pc)
[ -n "$config" ] && [ -n "$pc" ] || fail "no vriConfig.cmake or vri.pc under the prefix: $(cd "$prefix" && find . -type f)"
for doc in LICENSE CITATION.cff; do
  [ -n "$(find "$prefix/share/doc" -name "$doc")" ] || fail "$doc not installed under share/doc"
done

# Every tool: "<tool> (vri) <version>", then the commit, the build type and the compiler.
version=$(sed -n 's/^project(vri VERSION \([0-9.]*\) .*/\1/p' "$VRI_SOURCE/CMakeLists.txt")
[ -n "$version" ] || fail "no project version in CMakeLists.txt"
tools=0
for tool in "$bin"/vri-*; do
  name=$(basename "$tool")
  "$tool" --version > version.txt 2> version.err || fail "$name --version: exit $?: $(cat version.err)"
  [ "$(head -1 version.txt)" = "$name (vri) $version" ] || fail "$name --version: first line $(head -1 version.txt)"
  sed -n 2p version.txt | grep -Eq "^git commit ([0-9a-f]{12}(\+modified)?|unknown), $(cached CMAKE_BUILD_TYPE) build, " ||
    fail "$name --version: second line $(sed -n 2p version.txt)"
  [ ! -s version.err ] && [ "$(wc -l < version.txt)" -eq 2 ] || fail "$name --version: $(cat version.txt version.err)"
  tools=$((tools + 1))
done
[ "$tools" -ge 10 ] || fail "only $tools tools installed"

# The example, found through CMAKE_PREFIX_PATH only (no package registry), built with the build's compiler.
cmake -S "$VRI_SOURCE/examples/render_linear_field" -B example -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF -DCMAKE_CXX_COMPILER="$cxx" \
  ${launcher:+-DCMAKE_CXX_COMPILER_LAUNCHER="$launcher"} > example.log 2>&1 || { cat example.log >&2; fail "configuring the example"; }
[ "$(sed -n 's/^vri_DIR:PATH=//p' example/CMakeCache.txt)" = "$(dirname "$config")" ] ||
  fail "the example found vri elsewhere: $(grep '^vri_DIR' example/CMakeCache.txt)"
cmake --build example >> example.log 2>&1 || { cat example.log >&2; fail "building the example"; }
example/render_linear_field field.exr || fail "the example failed"

# The same scene through the installed vri-render: bitwise equal; and not an empty image.
tf="$VRI_SOURCE/experiments/tf/paper-a-linear.yaml"
"$bin/vri-render" --field linear --tf "$tf" --size 64x48 -q -o reference.exr
"$bin/vri-diff" reference.exr field.exr --fail 0 > diff.txt || fail "the example's image differs: $(cat diff.txt)"
printf 'points:\n  - [0, 0, 0, 0, 0]\n' > black.yaml
"$bin/vri-render" --field linear --tf black.yaml --size 64x48 -q -o black.exr
rc=0; "$bin/vri-diff" black.exr field.exr --fail 0.1 --failpercent 10 > diff.txt || rc=$?
[ "$rc" -eq 3 ] || fail "the example's image is nearly black (vri-diff exit $rc): $(cat diff.txt)"

# pkg-config: the example again, and every installed header in one translation unit.
export PKG_CONFIG_PATH="$(dirname "$pc")"
flags=$(pkg-config --cflags --libs vri) || fail "pkg-config vri: $flags"
# shellcheck disable=SC2086  # the flags are words
$launcher "$cxx" -std=c++20 -O2 -ffp-contract=off "$VRI_SOURCE/examples/render_linear_field/render_linear_field.cpp" \
  $flags -o pc-example 2> pc.log || { cat pc.log >&2; fail "building the example through vri.pc"; }
./pc-example pc-field.exr || fail "the example built through vri.pc failed"
"$bin/vri-diff" field.exr pc-field.exr --fail 0 > diff.txt || fail "the pkg-config build's image differs: $(cat diff.txt)"

(cd "$prefix/include" && find libvri -name '*.h' | LC_ALL=C sort) | sed 's/.*/#include "&"/' > all_headers.cpp
[ "$(wc -l < all_headers.cpp)" -ge 40 ] || fail "only $(wc -l < all_headers.cpp) headers installed"
foreign=$(grep -rlE '#include <(vulkan/|openvdb/|OpenImageIO/)' "$prefix/include" || true)
[ -z "$foreign" ] || fail "installed headers include OpenVDB, OpenImageIO or Vulkan: $foreign"
# shellcheck disable=SC2046
$launcher "$cxx" -std=c++20 -fsyntax-only $(pkg-config --cflags vri) all_headers.cpp 2> headers.log ||
  { cat headers.log >&2; fail "the installed headers do not compile from the prefix alone"; }

# The Python module, when the build has one: in the prefix's site-packages, and it renders there the same
# image as the installed vri-render.
python_module=none
if [ -n "$(find "$VRI_BUILD/python" -maxdepth 1 -name 'vri.*.so' 2> /dev/null)" ]; then
  site=$(find "$prefix/lib" -path '*/site-packages/vri.*.so' -printf '%h\n')
  [ -n "$site" ] || fail "the Python module is not installed in a site-packages under the prefix"
  PYTHONPATH="$site" "$(cached VRI_PYTHON_INTERPRETER)" -c '
import sys, vri
image, _ = vri.render(vri.LinearField(), vri.load_transfer_function(sys.argv[1]), vri.Camera(size=(64, 48)))
vri.write_exr("python.exr", image)' "$tf" || fail "the installed Python module failed"
  # A .vdb through the installed tools' and the installed Python module's OpenVDB module (lib/vri).
  head -c 64 /dev/urandom > v_4x4x4_uint8.raw
  "$prefix/bin/vri-convert" -q v_4x4x4_uint8.raw v.vdb || fail "the installed vri-convert cannot write a .vdb"
  PYTHONPATH="$site" "$(cached VRI_PYTHON_INTERPRETER)" -c '
import sys, vri
sys.exit(0 if vri.load_volume("v.vdb") is not None else 1)' || fail "the installed Python module cannot read a .vdb"
  "$bin/vri-diff" reference.exr python.exr --fail 0 > diff.txt || fail "the installed module's image differs: $(cat diff.txt)"
  python_module=${site#"$prefix"/}
fi
echo "install: $tools tools, $(wc -l < all_headers.cpp) headers, the example bitwise equal to vri-render," \
     "Python module: $python_module"
