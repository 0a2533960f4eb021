#!/usr/bin/env bash
# Under a control group's memory limit (a container's, a batch job's), a
# domain that needs more points than the limit allows stops refining with
# the device-memory warning and writes a valid mesh, instead of being killed
# by the kernel when it goes over the limit. The domain: a unit square with a
# square hole 1e-9 from its lower side; -pq30 needs ever smaller triangles
# along the channel between them.
# Needs a control group it can make (root, a writable cgroup v1 memory
# controller or cgroup v2 with the memory controller); otherwise it is
# skipped (exit status 77).
# Usage: memory_limit.sh CLMESH_BINARY SOURCE_DIR
set -euo pipefail
source "$(dirname "$0")/common.bash" "$@"
cd "$work"

limit=$((500 * 1024 * 1024))
group=""
cleanup() {
  if [[ -n "$group" ]]; then
    rmdir "$group" 2> /dev/null || true
  fi
  rm -rf "$work"
}
trap cleanup EXIT

# Makes a group with the limit; sets group (its folder), limit_file.
make_group() {
  local v1=/sys/fs/cgroup/memory v2=/sys/fs/cgroup
  if [[ -w "$v1" && -f "$v1/memory.limit_in_bytes" ]]; then
    group="$v1/clmesh-test-$$"
    mkdir "$group" 2> /dev/null && echo "$limit" > "$group/memory.limit_in_bytes" 2> /dev/null &&
      return 0
  elif [[ -w "$v2" && -f "$v2/cgroup.controllers" ]] && grep -qw memory "$v2/cgroup.controllers"; then
    echo +memory > "$v2/cgroup.subtree_control" 2> /dev/null || true
    group="$v2/clmesh-test-$$"
    mkdir "$group" 2> /dev/null && echo "$limit" > "$group/memory.max" 2> /dev/null && return 0
  fi
  return 1
}
if ! make_group; then
  echo "SKIP: no memory control group can be made here (needs root and a writable /sys/fs/cgroup)"
  exit 77
fi

cat > channel.poly << 'EOF'
8 2 0 0
1 0 0
2 1 0
3 1 1
4 0 1
5 0.2 1e-09
6 0.6 1e-09
7 0.6 0.5
8 0.2 0.5
8 0
1 1 2
2 2 3
3 3 4
4 4 1
5 5 6
6 6 7
7 7 8
8 8 5
1
1 0.4 0.25
EOF

# -C: a mesh that fails the exact check exits with status 1.
status=0
(
  echo "$BASHPID" > "$group/cgroup.procs"
  exec timeout 300 "$bin" -QC -pq30 channel.poly
) > out.txt 2> err.txt || status=$?
if [[ "$status" -ne 0 ]]; then
  fail "-pq30 under a $((limit >> 20)) MiB limit exited with $status (137: killed): $(cat err.txt)"
fi
if ! grep -q "the device's memory cannot hold more Steiner points" err.txt; then
  fail "no device-memory warning: $(cat err.txt)"
fi
points=$(head -1 channel.1.node 2> /dev/null | awk '{print $1}')
# Refinement went on until the limit was near: far more than the input's.
if [[ "${points:-0}" -lt 100000 ]]; then
  fail "only ${points:-no} vertices before stopping"
fi
finish memory_limit
