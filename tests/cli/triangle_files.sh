#!/usr/bin/env bash
# Triangle's remaining outputs and switches: -v (.v.node, .v.edge), -o2
# (six-node triangles), -g (.off), --vtk (.vtu), -P; -X -i -F -l -s accepted
# without effect; -u, -o3 refused; -h lists every switch. The files are read
# back by triangle_files.py, an independent reader, and compared with
# Triangle's own outputs in datasets/triangle-reference/ (their commands are
# listed in datasets/README.md).
# Usage: triangle_files.sh CLMESH_BINARY SOURCE_DIR [TEST_DATA_DIR]
set -euo pipefail
source "$(dirname "$0")/common.bash" "$@"
examples="${3:-$source_dir/../shared/data}/triangle-examples"
inputs="$examples/inputs"
references="$examples/reference-outputs"
checker="$(dirname "$0")/triangle_files.py"
checker="$(cd "$(dirname "$checker")" && pwd)/$(basename "$checker")"
cd "$work"
cp "$inputs/diamond_02_00009.node" "$inputs/spiral.node" "$inputs/A.poly" "$inputs/box.poly" .
cp "$inputs/A.poly" A.o2.poly
cp "$inputs/dots.node" dots.o2.node

# check WHAT ARGS...: runs the independent checker, a failure per problem.
check() {
  local report
  if ! report="$(python3 "$checker" "$@" 2>&1)"; then
    fail "$report"
  fi
}
want_file() { [[ -f "$1" ]] || fail "$1 was not written"; }
want_no_file() { [[ ! -e "$1" ]] || fail "$1 should not have been written"; }

# -v: Triangle's counts and rays, circumcentres, duality.
run -vQ diamond_02_00009.node
check voronoi diamond_02_00009.1 "$references/diamond_02_00009.1"
run -vQ spiral.node
check voronoi spiral.1 "$references/spiral.1"
run -pvQ A.poly
check voronoi A.1 "$references/A.1"
# Point attributes are interpolated: A's .v.node has its attribute column.
[[ "$(head -n 1 A.1.v.node | tr -s ' ')" == "29 2 1 0" ]] ||
  fail "A.1.v.node header: $(head -n 1 A.1.v.node)"
run -vqQ spiral.node
check voronoi spiral.1
# -z numbers the Voronoi vertices and edges from 0, rays keep -1.
run -vzQ spiral.node
check voronoi spiral.1
[[ "$(awk 'NR == 2 { print $1 }' spiral.1.v.edge)" == 0 ]] || fail "-vz: .v.edge not from 0"

# -o2: midpoints, shared, numbered after the vertices, Triangle's nodes.
run -po2Q A.o2.poly
check o2 A.o2.1 "$references/A.o2.1"
run -o2Q dots.o2.node
check o2 dots.o2.1 "$references/dots.o2.1"
run -pco2eQ box.poly
check o2 box.1
run -q30o2vQ spiral.node
check o2 spiral.1
check voronoi spiral.1

# -g and --vtk, read back.
run -gQ --vtk spiral.vtu spiral.node
check off spiral.1
check vtu spiral.vtu spiral.1
run -pAgQ --vtk A.vtu A.poly
check off A.1
check vtu A.vtu A.1
run -o2gQ --vtk dots.vtu dots.o2.node
check off dots.o2.1
check vtu dots.vtu dots.o2.1
run -pBQ --vtk box.vtu box.poly
check vtu box.vtu box.1
if grep -q 'Name="marker"' box.vtu; then fail "-B: the .vtu has markers"; fi
# -j leaves the jettisoned vertex out of the .off as of the .node.
printf '5 2 0 0\n1 0 0\n2 1 0\n3 0 1\n4 1 1\n5 1 0\n' > dup.node
run -jgQ --vtk dup.vtu dup.node
check off dup.1
check vtu dup.vtu dup.1

# Deterministic: the same files whatever the work-group size or the grid.
mkdir same1 same2 && cp dots.o2.node same1/ && cp dots.o2.node same2/
(cd same1 && "$bin" -vo2gQ --work-group 1 --grid 16 --vtk d.vtu dots.o2.node)
(cd same2 && "$bin" -vo2gQ --work-group 128 --vtk d.vtu dots.o2.node)
for f in dots.o2.1.node dots.o2.1.ele dots.o2.1.v.node dots.o2.1.v.edge dots.o2.1.off d.vtu; do
  cmp -s "same1/$f" "same2/$f" || fail "$f differs between work-group sizes and grids"
done

# -P: no .poly.
mkdir noPoly && cp A.poly noPoly/ && cd noPoly
run -pPQ A.poly
want_file A.1.node
want_no_file A.1.poly
cd "$work"

# -X -i -F -l -s change nothing; -V says so in one line.
mkdir plain same && cp A.poly plain/ && cp A.poly same/
(cd plain && "$bin" -pQ A.poly)
(cd same && "$bin" -pXiFlsQ A.poly)
for f in A.1.node A.1.ele A.1.poly; do
  cmp -s <(grep -v '^#' "plain/$f") <(grep -v '^#' "same/$f") || fail "-XiFls changed $f"
done
run -XiV spiral.node
[[ "$(grep -c -- '-X -i: accepted, no effect' stdout.txt)" == 1 ]] ||
  fail "-V does not say that -X -i have no effect: $(cat stdout.txt)"

# Refused: -u (with why), -o without 2.
expect "-u" 2 "-u" "callback" "not supported" -- -u spiral.node
expect "-o3" 2 "-o" "-o2" -- -o3 spiral.node

# All or nothing: a directory in the way of the .v.edge leaves no file.
mkdir blocked && cp spiral.node blocked/ && cd blocked && mkdir spiral.1.v.edge
expect "a directory named like the .v.edge" 1 "spiral.1.v.edge" -- -v spiral.node
want_no_file spiral.1.node
want_no_file spiral.1.v.node
cd "$work"

# -h names every switch of Triangle's usage line.
"$bin" -h > help.txt
for letter in p r q a u A c D j e v n g B P N E I O X z o Y S i F l s C Q V h; do
  grep -q -- "-$letter" help.txt || fail "-h does not mention -$letter"
done

finish triangle_files
