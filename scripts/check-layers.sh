#!/bin/bash
# The library's layers include one way only (README "Layout"): a file in a layer may include its own
# layer and those below it, never one above. Prints each wrong-way include as file:line and exits 1.
#   util < core < io, vulkan < render < experiment, report < tools/common < tools
# Usage: scripts/check-layers.sh [ROOT]   (ROOT: a source tree to check, default this repository)
set -euo pipefail
cd "${1:-$(dirname "$0")/..}"

# The layers each layer may include.
declare -A allowed=(
    [util]="util"
    [core]="util core"
    [io]="util core io"
    [vulkan]="util core vulkan"
    [render]="util core io vulkan render"
    [experiment]="util core io vulkan render experiment"
    [report]="util core io vulkan render report"
)

# Each file's layer from its path, then one grep over them all: a process per file made this check take
# 4 s and its test, which runs it on nine trees, 38 s.
status=0
files=()
while IFS= read -r -d '' file; do
    layer=${file#libvri/}
    layer=${layer%%/*}
    if [[ -z ${allowed[$layer]+known} ]]; then
        echo "$file: not in a known layer (libvri/<layer>/)"
        status=1
        continue
    fi
    files+=("$file")
done < <(find libvri -name '*.h' -print0 -o -name '*.cpp' -print0 | sort -z)
while IFS= read -r match; do  # FILE:LINE:#include "TARGET"
    file=${match%%:*}
    rest=${match#*:}
    line=${rest%%:*}
    target=${rest#*:#include \"}
    target=${target%\"}
    case "$target" in
        libvri/*/*) to=${target#libvri/}; to=${to%%/*} ;;
        common/*) to=common ;;
        *) continue ;;
    esac
    layer=${file#libvri/}
    layer=${layer%%/*}
    ok=${allowed[$layer]}
    if [[ " $ok " != *" $to "* ]]; then
        echo "$file:$line: includes \"$target\": the $layer layer may include only: $ok"
        status=1
    fi
done < <(((${#files[@]})) && grep -Hno '^#include "[^"]*"' "${files[@]}" || true)
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
