#!/usr/bin/env bash
# Every relative link of README.md, docs/ and the results gallery leads to a file, and every #anchor to a
# heading there (scripts/check-doc-links.py).
source "$(dirname "${BASH_SOURCE[0]}")/lib/scratch.sh"
/usr/bin/python3 "${VRI_SOURCE:?}/scripts/check-doc-links.py" "$VRI_SOURCE"
