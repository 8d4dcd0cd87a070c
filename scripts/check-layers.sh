#!/bin/bash
# The library's layers include one way only (README "Layout"): a file in a layer may include its own
# layer and those below it, never one above. Prints each wrong-way include as file:line and exits 1.
#   util < core < io, vulkan < render < experiment, report < tools/common < tools
# Usage: scripts/check-layers.sh [ROOT]   (ROOT: a source tree to check, default this repository)
set -euo pipefail
cd "${1:-$(dirname "$0")/..}"

allowed() {  # the layers a layer may include
    case "$1" in
        util) echo "util" ;;
        core) echo "util core" ;;
        io) echo "util core io" ;;
        vulkan) echo "util core vulkan" ;;
        render) echo "util core io vulkan render" ;;
        experiment) echo "util core io vulkan render experiment" ;;
        report) echo "util core io vulkan render report" ;;
        *) return 1 ;;
    esac
}

status=0
while IFS= read -r -d '' file; do
    layer=${file#libvri/}
    layer=${layer%%/*}
    ok=$(allowed "$layer") || { echo "$file: not in a known layer (libvri/<layer>/)"; status=1; continue; }
    while IFS=: read -r line target; do
        [[ -n $line ]] || continue
        case "$target" in
            libvri/*/*) to=${target#libvri/}; to=${to%%/*} ;;
            common/*) to=common ;;
            *) continue ;;
        esac
        if [[ " $ok " != *" $to "* ]]; then
            echo "$file:$line: includes \"$target\": the $layer layer may include only: $ok"
            status=1
        fi
    done < <(grep -no '^#include "[^"]*"' "$file" | sed 's/#include "\(.*\)"/\1/')
done < <(find libvri -name '*.h' -print0 -o -name '*.cpp' -print0 | sort -z)
# Third-party headers that belong to one layer only (README "Layout"): OpenVDB and OpenImageIO in io,
# Vulkan in vulkan, CLI11 in tools.
while IFS=: read -r file line header; do
    layer=${file#libvri/}; layer=${layer%%/*}
    case "$header" in
        openvdb/*|OpenImageIO/*) [[ $layer == io ]] && continue ;;
        vulkan/*) [[ $layer == vulkan ]] && continue ;;
        CLI/*) ;;
    esac
    echo "$file:$line: includes <$header>, which belongs to another layer"
    status=1
done < <(grep -rno '^#include <\(openvdb\|OpenImageIO\|vulkan\|CLI\)/[^>]*>' libvri | sed 's/#include <\(.*\)>/\1/')
exit $status
