#!/usr/bin/env bash
# The Simpson methods' tau h range (libvri/core/simpson_range.h): a render whose steps go beyond it warns
# once on stderr and its stats count the pixels; one within it is silent and counts none; the fixed-step
# methods have no such record.
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
bin=${VRI_BIN:?}
source "$(dirname "${BASH_SOURCE[0]}")/lib/blob.sh" && write_blob_volume
write_tf() {  # write_tf TAU
  printf 'points:\n  - [0.0, 0, 0, 0, 0]\n  - [0.3, 0, 0, 0, 0]\n  - [0.7, 1, 0.5, 0.2, %s]\n  - [1.0, 1, 1, 1, %s]\n' "$1" "$1" > tf.yaml
}
render() { "$bin/vri-render" --volume blob_8x8x8_uint8.raw --tf tf.yaml --size 16x12 --eye 4,4,-20 --target 4,4,4 -q "$@"; }
range() { /usr/bin/python3 -c "import json, sys; r = json.load(open(sys.argv[1]))['stats']['simpson_range']; print(r['$2'])" "$1"; }

write_tf 50
for method in "simpson --step 1" "coupled --h-max 4" "decoupled --h-max none"; do
  # shellcheck disable=SC2086
  render --method $method -o beyond.exr --stats beyond.json 2> err.txt || fail "$method: $(cat err.txt)"
  [ "$(wc -l < err.txt)" -eq 1 ] || fail "$method: expected one warning, got: $(cat err.txt)"
  beyond=$(range beyond.json pixels_beyond)
  [ "$beyond" -gt 0 ] || fail "$method: tau 50 at steps of a voxel and more, yet no pixel beyond the range"
  grep -Eq "^vri-render: warning: $beyond of 192 pixels took Simpson steps of tau h up to [0-9.e+]+, beyond 3.93, " err.txt ||
    fail "$method: the warning does not give the stats' count $beyond: $(cat err.txt)"
  /usr/bin/python3 -c "import sys; sys.exit(not float(sys.argv[1]) > 3.93)" "$(range beyond.json largest_tau_h)" ||
    fail "$method: largest tau h $(range beyond.json largest_tau_h) not beyond the limit"
done
render --method decoupled --h-max none --accepted-value paper -o paper.exr --stats paper.json 2> /dev/null
[ "$(range paper.json tau_h_limit)" = 3.62 ] || fail "paper B's accepted value: limit $(range paper.json tau_h_limit)"

write_tf 1
render --method simpson --step 1 -o within.exr --stats within.json 2> err.txt
[ ! -s err.txt ] || fail "tau h 1: unexpected messages: $(cat err.txt)"
[ "$(range within.json pixels_beyond)" -eq 0 ] || fail "tau h 1: pixels beyond the range"
render --method riemann --step 1 -o riemann.exr --stats riemann.json
! grep -q simpson_range riemann.json || fail "riemann records a Simpson range"
echo "simpson range: warned and counted beyond, silent within"
