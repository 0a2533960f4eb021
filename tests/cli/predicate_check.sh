#!/usr/bin/env bash
# The device's check of its exact predicates (runtime/predicate_check.cpp)
# refuses a device whose arithmetic is not exact: with kernel sources whose
# Two-Sum drops its rounding error (as a compiler that reassociates would),
# clmesh stops before meshing with a message naming the device and the
# predicate, exit status 1 and no output file; the true sources mesh. A
# pass is kept in the program cache: the next run with the same sources skips
# the check, and broken sources are still refused after it.
# Usage: predicate_check.sh CLMESH_BINARY SOURCE_DIR [TEST_DATA_DIR]
set -euo pipefail
source "$(dirname "$0")/common.bash" "$@"
cd "$work"
export CLMESH_CACHE_DIR="$work/cache"
cp "$source_dir/datasets/A.poly" .

cp -r "$source_dir/cl" broken
sed -i 's/  \*e = a_roundoff + b_roundoff;/  *e = a_roundoff;/' broken/predicates.h
! cmp -s "$source_dir/cl/predicates.h" broken/predicates.h || fail "the sed found no Two-Sum to break"

status=0
CLMESH_KERNEL_DIR="$work/broken" "$bin" -pq30 A.poly > out 2> err || status=$?
[[ $status == 1 ]] || fail "broken predicates: exit status $status, expected 1"
grep -q "gets the exact predicates wrong" err || fail "broken predicates: stderr: $(cat err)"
[[ ! -e A.1.node && ! -e A.1.ele ]] || fail "broken predicates: output files written"

# checks RUN: how many times RUN's profile launched the check's kernel.
checks() { awk '$1 == "evaluate_predicates" { print $4 }' "$1"; }
CLMESH_PROFILE=1 "$bin" -Q -pq30 A.poly 2> first || fail "true predicates: exit status $?"
[[ -s A.1.ele ]] || fail "true predicates: no A.1.ele"
[[ "$(checks first)" == 1 ]] || fail "true predicates: the check ran '$(checks first)' times"
CLMESH_PROFILE=1 "$bin" -Q -pq30 A.poly 2> second || fail "second run: exit status $?"
[[ -z "$(checks second)" ]] || fail "second run: the check ran again, not taken from the cache"

rm -f A.1.*
status=0
CLMESH_KERNEL_DIR="$work/broken" "$bin" -pq30 A.poly > out 2> err || status=$?
[[ $status == 1 ]] || fail "broken predicates after a pass: exit status $status, expected 1"
[[ ! -e A.1.node && ! -e A.1.ele ]] || fail "broken predicates after a pass: output files written"
finish predicate_check
