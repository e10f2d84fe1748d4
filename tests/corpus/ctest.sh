#!/bin/bash
# One model of the generated corpus as a ctest case (issue 36): made once
# into the build folder's cache, sampled, reconstructed and checked by
# run.py against its invariants (closed -> closed, manifold, no
# self-intersection, component count; open -> open, nothing off the data).
# Usage: ctest.sh MODEL BINARY CACHE_DIR
set -euo pipefail
model=$1 binary=$2 cache=$3
here=$(cd "$(dirname "$0")" && pwd)
python=/usr/bin/python3
mkdir -p "$cache"
"$python" "$here/generate.py" "$cache/models" --only "$model" >/dev/null
# A new build is checked afresh: run.py keeps the results a work folder holds.
rm -rf "$cache/work-$model"
exec "$python" "$here/run.py" "$binary" "$cache/models" "$cache/work-$model" --models "$model" --points 50000 --deltas 5
