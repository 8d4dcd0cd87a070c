#!/usr/bin/env bash
# The committed gallery is what `vri-run --gallery` makes of the committed manifests and tables, so
# every number a caption takes from a table ({{table:NAME:ROW:COLUMN}}) is in that table; a caption
# that cites a cell its table lacks stops the gallery with one line. The tables, CSVs and JSON files (which
# {{json:NAME:PATH}} citations and the heat-map scales read) are copied beside the manifests.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
bin=$VRI_BIN
mkdir results
for manifest in "$VRI_SOURCE"/results/*/manifest.json; do
  folder=$(dirname "$manifest") name=$(basename "$(dirname "$manifest")")
  mkdir "results/$name"
  cp "$manifest" "results/$name/"
  find "$folder" -maxdepth 1 \( -name '*.csv' -o -name '*.md' -o -name '*.json' \) -exec cp {} "results/$name/" \;
done
"$bin/vri-run" --gallery results 2> /dev/null
cmp results/README.md "$VRI_SOURCE/results/README.md" ||
  fail "results/README.md differs from the gallery of the committed manifests (run vri-run --gallery results): $(diff results/README.md "$VRI_SOURCE/results/README.md" | head -8)"

# A cited cell that is not in the data.
first=$(ls -d results/*/ | head -1)
sed -i 's/"agreement": "/"agreement": "{{table:no-such-table:a:b}} /' "$first/manifest.json"
rc=0
"$bin/vri-run" --gallery results 2> err.txt || rc=$?
[ "$rc" -eq 1 ] || fail "a caption citing a missing table: exit $rc, expected 1"
[ "$(wc -l < err.txt)" -eq 1 ] && grep -Eq '^vri-run: error: caption: \{\{table:no-such-table:a:b\}\}: results/[^/]+/no-such-table.csv: ' err.txt ||
  fail "unexpected message: $(cat err.txt)"
echo "gallery checks passed"
