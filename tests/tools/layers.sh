# The library's layers include one way only: scripts/check-layers.sh passes on the tree and catches a
# wrong-way include, a foreign library's header in the wrong layer, and a file outside any layer.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
check="$VRI_SOURCE/scripts/check-layers.sh"

"$check" || fail "the source tree has wrong-way includes (see above)"

copy_tree() { rm -rf tree && mkdir tree && cp -r "$VRI_SOURCE/src" tree/; }
expect_refused() {  # PATTERN: the check must fail and name the offending include
    if "$check" tree > out.txt 2>&1; then fail "check-layers accepted: $1"; fi
    grep -q -- "$1" out.txt || { cat out.txt >&2; fail "check-layers did not say: $1"; }
}

copy_tree
printf '#include "vri/experiment/experiment_spec.h"\n' >> tree/src/vri/core/box.cpp
expect_refused 'src/vri/core/box.cpp:.*includes "vri/experiment/experiment_spec.h": the core layer may include only: util core'

copy_tree
printf '#include "vri/io/image_io.h"\n' >> tree/src/vri/util/csv.h
expect_refused 'src/vri/util/csv.h:.*the util layer may include only: util$'

copy_tree
printf '#include "common/cli.h"\n' >> tree/src/vri/report/table.cpp
expect_refused 'src/vri/report/table.cpp:.*includes "common/cli.h"'

copy_tree
printf '#include <openvdb/openvdb.h>\n' >> tree/src/vri/core/volume.cpp
expect_refused 'src/vri/core/volume.cpp:.*<openvdb/openvdb.h>, which belongs to another layer'

copy_tree
printf '#include <vulkan/vulkan.h>\n' >> tree/src/vri/experiment/manifest.cpp
expect_refused 'src/vri/experiment/manifest.cpp:.*<vulkan/vulkan.h>'

copy_tree
mkdir tree/src/vri/misc && touch tree/src/vri/misc/x.h
expect_refused 'src/vri/misc/x.h: not in a known layer'
echo "layers: OK"
