#!/usr/bin/env bash
# The kernel cache ($CLMESH_CACHE_DIR) never fails a run: runs filling an
# empty cache at once all succeed with the same mesh and leave whole entries;
# truncated entries, a directory at an entry's name and a cache folder that
# is a file give the same mesh, nothing on stderr, and whole entries again.
# Usage: cache.sh CLMESH_BINARY SOURCE_DIR [TEST_DATA_DIR]
set -euo pipefail
source "$(dirname "$0")/common.bash" "$@"
inputs="${3:-$source_dir/../shared/data}/triangle-examples/inputs"
cd "$work"
export CLMESH_CACHE_DIR="$work/cache"

# mesh DIR: meshes A.poly (-p, several programs) in a fresh folder DIR in the
# background; DIR/status, DIR/err hold the exit status and stderr.
mesh() {
  mkdir "$1"
  cp "$inputs/A.poly" "$1/"
  (
    cd "$1"
    status=0
    "$bin" -pQ A.poly > out 2> err || status=$?
    echo "$status" > status
  ) &
}

# check DIR WHAT: DIR's run exited 0, wrote nothing on stderr and the mesh of
# the first run.
check() {
  [[ "$(cat "$1/status")" == 0 ]] || fail "$2: exit status $(cat "$1/status"): $(cat "$1/err")"
  [[ ! -s "$1/err" ]] || fail "$2: stderr: $(cat "$1/err")"
  local ext
  for ext in node ele poly; do
    cmp -s "$work/run0/A.1.$ext" "$1/A.1.$ext" || fail "$2: A.1.$ext differs from the first run's"
  done
}

# whole_entries WHAT: the cache holds only .bin entries (no partial file),
# each with clmesh's header, its payload's size and checksum (FNV-1a 64 over
# little-endian 8-byte words, then the bytes left).
whole_entries() {
  python3 - "$CLMESH_CACHE_DIR" <<'PY' || fail "$1: damaged cache entries"
import os, struct, sys
folder = sys.argv[1]
names = sorted(os.listdir(folder))
bad = [n for n in names if not n.endswith(".bin") or not os.path.isfile(os.path.join(folder, n))]
for name in names:
    if name in bad:
        continue
    data = open(os.path.join(folder, name), "rb").read()
    magic, version, header, key0, key1, size, checksum = struct.unpack_from("<8sIIQQQQ", data)
    payload = data[header:]
    hash = 0xcbf29ce484222325
    whole = len(payload) // 8 * 8
    for word in struct.unpack_from("<%dQ" % (whole // 8), payload):
        hash = ((hash ^ word) * 0x100000001b3) & 0xFFFFFFFFFFFFFFFF
    for byte in payload[whole:]:
        hash = ((hash ^ byte) * 0x100000001b3) & 0xFFFFFFFFFFFFFFFF
    if (magic != b"clmeshPB" or version != 1 or size != len(payload) or hash != checksum
            or name != "%016x%016x.bin" % (key0, key1)):
        bad.append(name)
if not names or bad:
    print("entries:", names, "bad:", bad, file=sys.stderr)
    sys.exit(1)
PY
}

# Four runs fill the empty cache at once.
for run in 0 1 2 3; do
  mesh "run$run"
done
wait
for run in 0 1 2 3; do
  check "run$run" "run $run of 4 at once on an empty cache"
done
whole_entries "after 4 runs at once"
entries="$(ls "$CLMESH_CACHE_DIR")"

# A run from the cache.
mesh cached
wait
check cached "a run from the cache"
[[ "$(ls "$CLMESH_CACHE_DIR")" == "$entries" ]] || fail "a run from the cache changed its entries"

# Every entry cut to half its size (a full disk, a killed write).
for entry in "$CLMESH_CACHE_DIR"/*.bin; do
  truncate -s "$(($(stat -c %s "$entry") / 2))" "$entry"
done
mesh truncated
wait
check truncated "truncated entries"
whole_entries "after truncated entries"
[[ "$(ls "$CLMESH_CACHE_DIR")" == "$entries" ]] || fail "truncated entries: not the same entries"

# An entry's name taken by a directory (empty: replaced).
first="$(ls "$CLMESH_CACHE_DIR" | head -n 1)"
rm "$CLMESH_CACHE_DIR/$first"
mkdir "$CLMESH_CACHE_DIR/$first"
mesh directory
wait
check directory "an entry's name taken by a directory"
whole_entries "after a directory at an entry's name"

# The cache folder is a file.
export CLMESH_CACHE_DIR="$work/not-a-folder"
echo "not a folder" > "$CLMESH_CACHE_DIR"
mesh file
wait
check file "a cache folder that is a file"
[[ "$(cat "$CLMESH_CACHE_DIR")" == "not a folder" ]] || fail "the file in the cache folder's place changed"

finish cache
