# The library's layers include one way only: scripts/check-layers.sh passes on the tree and catches a
# wrong-way include, a foreign library's header in the wrong layer, and a file outside any layer.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
check="$VRI_SOURCE/scripts/check-layers.sh"

"$check" || fail "the source tree has wrong-way includes (see above)"

copy_tree() { rm -rf tree && mkdir tree && cp -r "$VRI_SOURCE/libvri" tree/; }
expect_refused() {  # PATTERN: the check must fail and name the offending include
    if "$check" tree > out.txt 2>&1; then fail "check-layers accepted: $1"; fi
    grep -q -- "$1" out.txt || { cat out.txt >&2; fail "check-layers did not say: $1"; }
}

copy_tree
printf '#include "libvri/experiment/experiment_spec.h"\n' >> tree/libvri/core/box.cpp
expect_refused 'libvri/core/box.cpp:.*includes "libvri/experiment/experiment_spec.h": the core layer may include only: util core'

copy_tree
printf '#include "libvri/io/image_io.h"\n' >> tree/libvri/util/csv.h
expect_refused 'libvri/util/csv.h:.*the util layer may include only: util$'

copy_tree
printf '#include "common/cli.h"\n' >> tree/libvri/report/table.cpp
expect_refused 'libvri/report/table.cpp:.*includes "common/cli.h"'

copy_tree
printf '#include <openvdb/openvdb.h>\n' >> tree/libvri/core/volume.cpp
expect_refused 'libvri/core/volume.cpp:.*<openvdb/openvdb.h>, which belongs to another layer'

copy_tree
printf '#include <vulkan/vulkan.h>\n' >> tree/libvri/experiment/manifest.cpp
expect_refused 'libvri/experiment/manifest.cpp:.*<vulkan/vulkan.h>'

copy_tree
mkdir tree/libvri/misc && touch tree/libvri/misc/x.h
expect_refused 'libvri/misc/x.h: not in a known layer'
echo "layers: OK"
