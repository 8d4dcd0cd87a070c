#!/usr/bin/env bash
# The committed gallery (results/README.md and the viewer's pages) is what `vri-run --gallery` makes of the
# committed manifests, tables and PNGs, so
# every number a caption takes from a table ({{table:NAME:ROW:COLUMN}}) is in that table; a caption
# that cites a cell its table lacks stops the gallery with one line. The tables, CSVs and JSON files (which
# {{json:NAME:PATH}} citations and the heat-map scales read) are copied beside the manifests.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
bin=$VRI_BIN
mkdir results
for manifest in "$VRI_SOURCE"/results/*/manifest.json; do
  folder=$(dirname "$manifest") name=$(basename "$(dirname "$manifest")")
  mkdir "results/$name"
  find "$folder" -maxdepth 1 \( -name '*.csv' -o -name '*.md' -o -name '*.json' \) -exec cp -t "results/$name/" {} +
  # The PNGs give the viewer's pages each image's size: linked where the file system allows, else copied
  # (one cp a folder: a process a file took a third of the test's time).
  pngs=("$folder"/*.png)
  [ -f "${pngs[0]}" ] || continue
  cp --link -t "results/$name/" "${pngs[@]}" 2> /dev/null || { rm -f "results/$name/"*.png && cp -t "results/$name/" "${pngs[@]}"; }
done
# The pages scripts wrote (make bricks-slurm's), which the index lists after the experiments; the long sections'
# pages copied with them are written again.
find "$VRI_SOURCE/results" -maxdepth 1 -name '*.md' ! -name README.md -exec cp {} results/ \;
"$bin/vri-run" --gallery results 2> /dev/null
# README.md, the long sections' own pages, and the viewer: its index, a page per experiment, its script and style.
for page in results/*.md results/index.html results/*/index.html results/viewer/vri-viewer.js results/viewer/vri-viewer.css; do
  cmp "$page" "$VRI_SOURCE/$page" ||
    fail "$page differs from the gallery of the committed manifests (run vri-run --gallery results): $(diff "$page" "$VRI_SOURCE/$page" | head -8)"
done
# The index: one row per experiment, in the papers' order (paper A's items, then paper B's, then own studies),
# then the script pages.
rows=$(grep -c '^| \(Paper [AB], \|own study\)' results/README.md)
[ "$rows" -eq "$(ls results/*/manifest.json | wc -l)" ] || fail "the index has $rows rows for $(ls results/*/manifest.json | wc -l) experiments"
grep -o '^| \(Paper [AB]\|own study\|written by a script\)' results/README.md | uniq | tr '\n' ';' |
  grep -qx '| Paper A;| Paper B;| own study;| written by a script;' ||
  fail "the index is not in the papers' order: $(grep -o '^| \(Paper [AB]\|own study\)' results/README.md | uniq | tr '\n' ' ')"

# A cited cell that is not in the data.
first=$(ls -d results/*/ | head -1)
sed -i 's/"agreement": "/"agreement": "{{table:no-such-table:a:b}} /' "$first/manifest.json"
rc=0
"$bin/vri-run" --gallery results 2> err.txt || rc=$?
[ "$rc" -eq 1 ] || fail "a caption citing a missing table: exit $rc, expected 1"
[ "$(wc -l < err.txt)" -eq 1 ] && grep -Eq '^vri-run: error: caption: \{\{table:no-such-table:a:b\}\}: results/[^/]+/no-such-table.csv: ' err.txt ||
  fail "unexpected message: $(cat err.txt)"
echo "gallery checks passed"
