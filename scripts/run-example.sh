#!/usr/bin/env bash
# Build clmesh (Release) and mesh a bundled example, then show where the
# result is and print its statistics.
#
#   bash scripts/run-example.sh [NAME]
#
# NAME is a .node file under datasets/ without the extension (default
# greenland: 33,343 points of the Greenland coastline, from drufat/triangle,
# LGPL-3.0; see datasets/README.md).  Other choices: spiral, dots,
# delaunator/ukraine, ...  The outputs go to build/example/, not datasets/.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

name=${1:-greenland}
src=datasets/$name.node
if [[ ! -f $src ]]; then
  echo "run-example.sh: no $src" >&2
  exit 2
fi

bash scripts/deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)" --target clmesh_cli

out=build/example
base=$(basename "$name")
mkdir -p "$out"
cp "$src" "$out/$base.node"

# -V: verbose; writes $base.1.node and $base.1.ele next to the copy.
build/clmesh -V --svg "$out/$base.1.svg" --stats-json "$out/$base.stats.json" "$out/$base.node"

echo
echo "Mesh:  $out/$base.1.node, $out/$base.1.ele"
echo "SVG:   $PWD/$out/$base.1.svg  (open it in a web browser)"
echo "Stats: $out/$base.stats.json"
python3 -m json.tool "$out/$base.stats.json" 2>/dev/null || cat "$out/$base.stats.json"
