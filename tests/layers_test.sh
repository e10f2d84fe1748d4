#!/bin/bash
# The layer check (cmake/check_layers.cmake) passes on src/ and stops a
# back-edge: a copy of src/ where features/ includes an eval/ header fails,
# naming the file; so does a copy with a raw tbb::parallel_for.
set -euo pipefail
root=$1
layers=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake -DSOURCE_DIR="$root/src" "-DLAYERS=$layers" -P "$root/cmake/check_layers.cmake"
cp -r "$root/src" "$work/src"
mkdir -p "$work/src/eval"
echo '#pragma once' > "$work/src/eval/upper.h"
printf '#include "eval/upper.h"\n' > "$work/src/features/back_edge.cpp"
if cmake -DSOURCE_DIR="$work/src" "-DLAYERS=$layers" -P "$root/cmake/check_layers.cmake" 2> "$work/err"; then
  echo "a back-edge from features/ to eval/ passed the layer check" >&2
  exit 1
fi
grep -q "features/back_edge.cpp: includes eval/" "$work/err" || { cat "$work/err" >&2; exit 1; }
rm "$work/src/features/back_edge.cpp"
printf 'void f() { tbb::parallel_for(0, 4, [](int) {}); }\n' > "$work/src/pointset/raw_loop.cpp"
if cmake -DSOURCE_DIR="$work/src" "-DLAYERS=$layers" -P "$root/cmake/check_layers.cmake" 2> "$work/err"; then
  echo "a raw tbb::parallel_for in pointset/ passed the layer check" >&2
  exit 1
fi
grep -q "pointset/raw_loop.cpp: calls tbb::parallel_for" "$work/err" || { cat "$work/err" >&2; exit 1; }
