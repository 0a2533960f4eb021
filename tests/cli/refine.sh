#!/usr/bin/env bash
# -r's files, as Triangle reads and names them: name.node (or the vertices
# of name.poly with -p), name.ele, name.area (-a alone); an input named .ele
# implies -r, .area -ra; name.1 gives name.2.*; -I is refused; several inputs
# in one run. Bad meshes: one 'clmesh: FILE:LINE: ...' line, exit status 1,
# no file written. (The refined meshes themselves: refine_mesh.sh.)
# Usage: refine.sh CLMESH_BINARY SOURCE_DIR
set -euo pipefail
source "$(dirname "$0")/common.bash" "$@"
mkdir "$work/files" "$work/bad"

want_file() { [[ -f "$1" ]] || fail "$1 was not written"; }
want_no_file() { [[ ! -e "$1" ]] || fail "$1 should not have been written"; }
# opened WHAT FILES...: the run's 'Opening' lines name FILES, in that order.
opened() {
  local what="$1"
  shift
  local want
  want="$(printf 'Opening %s.\n' "$@")"
  local got
  got="$(grep '^Opening ' stdout.txt || true)"
  [[ "$got" == "$want" ]] || fail "$what: opened '$got', wanted '$want'"
}

# A unit square cut along a diagonal, numbered from 1, two attributes a
# triangle, and its .area and .poly (a segment on the other diagonal's half).
square() {
  printf '5 2 0 1\n1 0 0 1\n2 1 0 1\n3 1 1 1\n4 0 1 1\n5 0.5 0.25 0\n' > "$1.node"
  printf '4 3 2\n1 1 2 5 1 10\n2 2 3 5 2 20\n3 3 1 5 3 30\n4 1 3 4 4 40\n' > "$1.ele"
  printf '4\n1 0.01\n2 -1\n3 0\n4 0.02\n' > "$1.area"
  printf '0 2 0 1\n1 1\n1 1 3 7\n0\n' > "$1.poly"
}

# ---------------------------------------------------------------------------
# Which files are read and written.
# ---------------------------------------------------------------------------
cd "$work/files"
square sq.1
run -r sq.1
opened "-r" sq.1.node sq.1.ele
want_file sq.2.node
want_file sq.2.ele
want_no_file sq.2.poly
grep -q '^  Input triangles: 4$' stdout.txt || fail "-r: no 'Input triangles: 4' line"
rm sq.2.*

run -ra sq.1.node
opened "-ra" sq.1.node sq.1.ele sq.1.area
want_file sq.2.ele
rm sq.2.*
run -ra -a0.5 sq.1
opened "-ra -a0.5" sq.1.node sq.1.ele sq.1.area
rm sq.2.*

run sq.1.ele
opened ".ele implies -r" sq.1.node sq.1.ele
want_file sq.2.ele
rm sq.2.*

run sq.1.area
opened ".area implies -ra" sq.1.node sq.1.ele sq.1.area
want_file sq.2.ele
rm sq.2.*

run -rp sq.1
opened "-rp, vertices in the .node" sq.1.poly sq.1.node sq.1.ele
want_file sq.2.poly
rm sq.2.*

# A .poly that lists vertices: those are the mesh's, the .node is not read.
mkdir listed && cd listed
square sq
rm sq.node
printf '5 2 0 1\n1 0 0 1\n2 1 0 1\n3 1 1 1\n4 0 1 1\n5 0.5 0.25 0\n1 1\n1 1 3 7\n0\n' > sq.poly
run -rp sq
opened "-rp, vertices in the .poly" sq.poly sq.ele
want_file sq.1.node
want_file sq.1.ele
want_file sq.1.poly
cd ..

# A vertex that no triangle uses (inside one here) stays out of the mesh and
# keeps its number, as in Triangle.
cp sq.1.node unused.node
printf '2 3 0\n1 1 2 3\n2 1 3 4\n' > unused.ele
run -rCQ unused
want_file unused.1.ele
[[ "$(awk '!/^#/ && NF { print $1; exit }' unused.1.node)" == 5 ]] ||
  fail "-r: the unused vertex is not in the .node"
if awk 'NR > 1 && !/^#/ && ($2 == 5 || $3 == 5 || $4 == 5)' unused.1.ele | grep -q .; then
  fail "-r: a triangle uses the unused vertex"
fi

# Zero-based input, and no iteration number in the input's name.
printf '4 2 0 0\n0 0 0\n1 2 0\n2 2 2\n3 0 2\n' > z.node
printf '2 3 0\n0 0 1 2\n1 0 2 3\n' > z.ele
run -r z
want_file z.1.node
want_file z.1.ele
[[ "$(grep -v '^#' z.1.node | sed -n 2p | awk '{print $1}')" == 0 ]] ||
  fail "-r: a zero-based input gives a zero-based output"

# -I would write the .ele over the input's: refused, as Triangle does.
expect "-rI" 2 "-I" "-r" -- -rI sq.1
expect "-I with an .ele input" 2 "-I" "-r" -- -I sq.1.ele

# ---------------------------------------------------------------------------
# Bad meshes: the file and line, exit 1, nothing written.
# ---------------------------------------------------------------------------
cd "$work/bad"
square sq
cp sq.node missing.node
printf '2 3 0\n1 1 2 5\n2 2 3 6\n' > missing.ele
cp sq.node clockwise.node
printf '2 3 0\n1 1 2 5\n2 2 5 3\n' > clockwise.ele
cp sq.node overlap.node
printf '2 3 0\n1 1 2 5\n2 1 2 3\n' > overlap.ele
cp sq.node short.node
printf '2 3 1\n1 1 2 5 1\n2 2 3 5\n' > short.ele
cp sq.node sequence.node
printf '2 3 0\n1 1 2 5\n3 2 3 5\n' > sequence.ele
cp sq.node count.node
cp sq.ele count.ele
printf '3\n1 0.1\n2 0.1\n3 0.1\n' > count.area
cp sq.node word.node
cp sq.ele word.ele
printf '4\n1 0.1\n2 small\n3 0.1\n4 0.1\n' > word.area
cp sq.node noarea.node
cp sq.ele noarea.ele
cp sq.node noele.node

expect "corner out of range" 1 "missing.ele:3:" "corner 6 of triangle 2" "not a vertex" \
  -- -r missing
expect "clockwise triangle" 1 "clockwise.ele:3:" "triangle 2" "clockwise" -- -rq clockwise
expect "overlapping triangles" 1 "overlap.ele:3:" "triangle 2" "overlaps triangle 1" -- -r overlap
# Overlaps that share no edge are found on the device; the message names
# one of the triangles.
cp sq.node crossing.node
printf '2 3 0\n1 1 2 3\n2 1 5 4\n' > crossing.ele
expect "overlapping triangles sharing no edge" 1 "clmesh: crossing.ele:2: triangle 1: it overlaps" -- -rq crossing
expect "missing attribute" 1 "short.ele:3:" "expected 5" -- -r short.ele
expect "triangle ids out of sequence" 1 "sequence.ele:3:" "out of sequence" -- -r sequence
expect ".area count differs from the .ele's" 1 "count.area:1:" "3 triangles" "has 4" \
  -- -ra count
expect "non-numeric area" 1 "word.area:3:" "'small'" "not a number" -- -rq30a word
expect "missing .area with -ra" 1 "noarea.area" "cannot open" -- -ra noarea
expect "missing .ele" 1 "noele.ele" "cannot open" -- -r noele.node
expect "missing .node" 1 "nothing.node" "cannot open" -- nothing.ele
expect "missing .poly with -rp" 1 "noele.poly" "cannot open" -- -rp noele

# ---------------------------------------------------------------------------
# Several inputs with -r: a bad one gets its message, the others are written.
# ---------------------------------------------------------------------------
mkdir "$work/batch" && cd "$work/batch"
square a.1
square b.1
cp "$work/bad/clockwise.node" c.1.node
cp "$work/bad/clockwise.ele" c.1.ele
status=0
"$bin" -rQ a.1 c.1 b.1.ele > stdout.txt 2> stderr.txt || status=$?
[[ "$status" == 1 ]] || fail "batch with a bad mesh: exit status $status, wanted 1"
grep -q '^clmesh: c.1.ele:3: triangle 2: ' stderr.txt ||
  fail "batch: no message naming c.1.ele:3: $(cat stderr.txt)"
grep -q '1 of 3 inputs failed' stderr.txt || fail "batch: no summary line: $(cat stderr.txt)"
for f in a.2.node a.2.ele b.2.node b.2.ele; do
  want_file "$f"
done
want_no_file c.2.ele
want_no_file c.2.node

finish refine
