#!/usr/bin/env bash
# Decodes each real LAZ tile with laz-perf (npm) and compares it with the
# library's reader point by point (tests/unit/laz_oracle_test.cpp); also the
# decode rate of both, for the benchmark. Exit 77 (a skip) when Node.js or
# the tiles are absent.
# usage: run.sh SOURCE_DIR WORK_DIR SHARPMESH_TESTS LIDAR_DIR
set -euo pipefail
source=$1 work=$2 tests=$3 lidar=$4
command -v node >/dev/null && command -v npm >/dev/null || { echo "skipped: Node.js and npm are not installed"; exit 77; }
compgen -G "$lidar/*.laz" >/dev/null || { echo "skipped: no LAZ tiles in $lidar"; exit 77; }
mkdir -p "$work"
cp "$source/tests/laz_oracle/package.json" "$source/tests/laz_oracle/package-lock.json" "$source/tests/laz_oracle/decode.js" "$work/"
if ! cmp -s "$work/package-lock.json" "$work/node_modules/.package-lock.json" 2>/dev/null; then
  (cd "$work" && npm ci --no-audit --no-fund --loglevel=error)
fi
for tile in "$lidar"/*.laz; do
  records="$work/$(basename "$tile").records"
  node "$work/decode.js" "$tile" "$records"
  SHARPMESH_LAZ_ORACLE="$tile:$records" "$tests" --gtest_filter='LazOracle.*' --gtest_brief=1
  rm -f "$records"
done
