#!/usr/bin/env bash
# Installs the built clmesh into a temporary prefix, then configures, builds
# and runs the consumer project beside this script against it.
# Usage: run.sh CMAKE BUILD_DIR [CXX_COMPILER]
set -euo pipefail
cmake="$1" build="$2" compiler="${3:-}"
here="$(cd "$(dirname "$0")" && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

"$cmake" --install "$build" --prefix "$work/prefix" > "$work/install.log" ||
  { cat "$work/install.log"; exit 1; }
for f in bin/clmesh include/clmesh/clmesh.hpp include/clmesh/version.hpp; do
  [[ -e "$work/prefix/$f" ]] || { echo "FAIL: $f not installed" >&2; exit 1; }
done
"$work/prefix/bin/clmesh" --version

"$cmake" -S "$here" -B "$work/consumer" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$work/prefix" ${compiler:+-DCMAKE_CXX_COMPILER="$compiler"} > "$work/configure.log" ||
  { cat "$work/configure.log"; exit 1; }
"$cmake" --build "$work/consumer" > "$work/build.log" || { cat "$work/build.log"; exit 1; }
"$work/consumer/consumer"
echo "install: the consumer built and ran against $work/prefix"
