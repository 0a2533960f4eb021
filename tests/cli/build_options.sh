#!/usr/bin/env bash
# CLMESH_BUILD_OPTIONS (docs/reference.md): its options reach the device's
# compiler, with the same meshes; options that relax IEEE arithmetic are
# refused before any program is built, as an option error (exit status 2),
# with no output file. The device sources declare every function static.
# Usage: build_options.sh CLMESH_BINARY SOURCE_DIR [TEST_DATA_DIR]
set -euo pipefail
source "$(dirname "$0")/common.bash" "$@"
cd "$work"
export CLMESH_CACHE_DIR="$work/cache"
cp "$source_dir/datasets/dots.node" .

for relaxing in -cl-fast-relaxed-math "-w -cl-mad-enable" -cl-unsafe-math-optimizations; do
  status=0
  CLMESH_BUILD_OPTIONS="$relaxing" "$bin" dots.node > out 2> err || status=$?
  [[ $status == 2 ]] || fail "$relaxing: exit status $status, expected 2 (an option error)"
  grep -q "CLMESH_BUILD_OPTIONS '$relaxing' relaxes IEEE arithmetic" err ||
    fail "$relaxing: stderr: $(cat err)"
  [[ ! -e dots.1.node && ! -e dots.1.ele ]] || fail "$relaxing: output files written"
done

# An option the compiler does not know fails the first build, named.
status=0
CLMESH_BUILD_OPTIONS=-cl-no-such-option "$bin" dots.node > out 2> err || status=$?
[[ $status != 0 ]] || fail "an unknown build option was accepted"
grep -q "predicate_check.cl" err || fail "unknown build option: stderr: $(cat err)"
[[ ! -e dots.1.node && ! -e dots.1.ele ]] || fail "unknown build option: output files written"

# Every device function is static: a plain C99 inline function has no
# external definition, so a compiler that keeps the call (NVIDIA's with
# -cl-opt-disable) cannot link the program.
if plain=$(grep -nE '^inline ' "$source_dir"/cl/*.cl "$source_dir"/cl/*.h); then
  fail "device functions declared inline without static: $plain"
fi

"$bin" -Q dots.node
mv dots.1.ele plain.ele
CLMESH_BUILD_OPTIONS=-w "$bin" -Q dots.node
cmp -s <(grep -v '^#' plain.ele) <(grep -v '^#' dots.1.ele) || fail "-w changed the mesh"

# The exact predicate stages inlined as a GPU builds them (cl/predicates.h),
# on the GPU paths: the predicate check passes and the quality mesh is the same.
cp "$source_dir/datasets/A.poly" .
"$bin" -Q -pq30 A.poly
mv A.1.ele A-plain.ele
status=0
CLMESH_DEVICE_PATHS=gpu CLMESH_BUILD_OPTIONS=-DCLM_EXACT_INLINE "$bin" -Q -pq30 A.poly 2> err ||
  status=$?
[[ $status == 0 ]] || fail "-DCLM_EXACT_INLINE: exit status $status: $(cat err)"
cmp -s <(grep -v '^#' A-plain.ele) <(grep -v '^#' A.1.ele) ||
  fail "the exact stages inlined changed the mesh"
finish build_options
