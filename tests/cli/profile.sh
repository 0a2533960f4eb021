#!/usr/bin/env bash
# CLMESH_PROFILE (docs/reference.md): at exit, every kernel launched with its
# launches, and the host's calls into the driver by cause with their counts;
# the mesh is the one of a run without it. In a batch each worker reports its
# own inputs.
# Usage: profile.sh CLMESH_BINARY SOURCE_DIR [TEST_DATA_DIR]
set -euo pipefail
source "$(dirname "$0")/common.bash" "$@"
cd "$work"
cp "$source_dir/datasets/A.poly" .

run -Q -pq30 A.poly
mv A.1.ele plain.ele
CLMESH_PROFILE=1 run -Q -pq30 A.poly
cmp -s <(grep -v '^#' plain.ele) <(grep -v '^#' A.1.ele) || fail "the profile changed the mesh"
# count CAUSE: the calls under CAUSE (0 when it is missing).
count() { awk -v cause="$1" '$1 == "host:" && index($0, cause) { print $(NF - 1) }' stderr.txt; }
for cause in "blocking read" "buffer creation" "kernel creation"; do
  [[ "$(count "$cause")" -gt 0 ]] 2> /dev/null || fail "no '$cause' calls counted: $(cat stderr.txt)"
done
grep -qE '^flipflop_passes_in_group +[0-9.]+ s +[1-9][0-9]* launches' stderr.txt ||
  fail "no flipflop_passes_in_group launches counted: $(cat stderr.txt)"

# A batch of two: a report from the worker, counting the kernels of both.
cp A.poly B.poly
CLMESH_PROFILE=1 run -Q -pq30 --jobs 1 A.poly B.poly
one=$(awk '$1 == "flipflop_passes_in_group" { print $4 }' stderr.txt)
CLMESH_PROFILE=1 run -Q -pq30 A.poly
single=$(awk '$1 == "flipflop_passes_in_group" { print $4 }' stderr.txt)
[[ "$one" == $((2 * single)) ]] || fail "batch of two: $one flipflop_passes_in_group launches, one input: $single"
finish profile
