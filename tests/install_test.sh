#!/usr/bin/env bash
# The CMake package as a user meets it: install the build tree into a fresh
# prefix (no root), build examples/cpp against it with find_package(sharpmesh)
# and run it on a sampled cube, whose mesh must come out closed.
# usage: install_test.sh BUILD_DIR SOURCE_DIR SHARPMESH_CLI DATA_DIR
set -euo pipefail
build=$1 source=$2 cli=$3 data=$4
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" >/dev/null
cmake -S "$source/examples/cpp" -B "$work/example" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
cmake --build "$work/example" >/dev/null
"$cli" sample "$data/meshes/cube.off" -n 5000 --seed 1 -o "$work/cube.xyz" -q
"$work/example/reconstruct_cloud" "$work/cube.xyz" "$work/cube.ply"
"$cli" eval "$work/cube.ply" --reference "$data/meshes/cube.off" --json "$work/eval.json" -q
/usr/bin/python3 - "$work/eval.json" <<'PY'
import json, sys
t = json.load(open(sys.argv[1]))["evaluation"]["topology"]
assert t["closed"] and not t["self_intersecting"], t
PY
# Usage errors exit 2 and say how to call it.
set +e
"$work/example/reconstruct_cloud" 2>"$work/usage.txt"
status=$?
set -e
[[ $status -eq 2 ]] || { echo "usage error exited $status, not 2"; exit 1; }
grep -q "usage:" "$work/usage.txt"
# One version string: the command's, the package's and the header's agree.
version=$(sed -n 's/^#define SHARPMESH_VERSION "\(.*\)"$/\1/p' "$work/prefix/include/sharpmesh/version.h")
[[ -n "$version" && "$("$work/prefix/bin/sharpmesh" --version)" == "sharpmesh $version" ]] || { echo "versions differ"; exit 1; }
grep -q "PACKAGE_VERSION \"$version\"" "$work/prefix/lib/cmake/sharpmesh/sharpmeshConfigVersion.cmake"
