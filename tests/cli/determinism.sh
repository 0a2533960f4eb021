#!/usr/bin/env bash
# The mesh files do not depend on the run, the Voronoi grid, the first
# triangulation's construction or the work-group size: .node, .ele and .neigh
# (.poly for PSLGs) must be byte-identical.
# Usage: determinism.sh CLMESH_BINARY SOURCE_DIR
set -euo pipefail
source "$(dirname "$0")/common.bash" "$@"
cd "$work"


python3 - <<'PY'
import random
rng = random.Random(20240601)
points = [(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)) for _ in range(3000)]
points += points[:25]                                   # a few duplicates
points += [(round(x, 2), round(y, 2)) for x, y in points[100:400]]  # near-coincident
with open("random.node", "w") as out:
    out.write(f"{len(points)} 2 0 0\n")
    for i, (x, y) in enumerate(points, 1):
        out.write(f"{i} {x!r} {y!r}\n")
with open("lattice.node", "w") as out:                  # cocircular everywhere
    out.write("400 2 1 1\n")
    for i in range(400):
        out.write(f"{i} {i % 20} {i // 20} {i * 0.5} {i % 3}\n")
PY

# Meshes INPUT.node in a fresh folder DIR with the given switches (-nQC: every
# run is also checked with exact predicates); fails the test and returns 1
# when clmesh does.
mesh_in() {
  local dir="$1" input="$2" status=0
  shift 2
  mkdir "$dir"
  cp "$work/$input.node" "$dir/"
  (cd "$dir" && "$bin" -nQC "$@" "$input.node") > "$dir.log" 2>&1 || status=$?
  if [[ "$status" -ne 0 ]]; then
    fail "$input with '$*' exited with $status: $(cat "$dir.log")"
    return 1
  fi
}

# The .node, .ele and .neigh files of INPUT in DIR must equal those in REFERENCE.
same_mesh() {
  local reference="$1" dir="$2" input="$3" what="$4" ext
  for ext in node ele neigh; do
    cmp -s "$reference/$input.1.$ext" "$dir/$input.1.$ext" ||
      fail "$input.1.$ext differs $what"
  done
}

configs=("" "" "--grid 64" "--grid 512" "--work-group 1" "--work-group 128" "--grid 64 --work-group 1"
         "--construction fan" "--construction voronoi")

for input in random lattice; do
  for index in "${!configs[@]}"; do
    config="${configs[$index]}"
    # shellcheck disable=SC2086  # config holds separate arguments
    mesh_in "$work/$input.$index" "$input" $config || continue
    [[ "$index" -eq 0 ]] ||
      same_mesh "$work/$input.0" "$work/$input.$index" "$input" \
        "between '${configs[0]}' and '$config'"
  done
done

# Refinement (both algorithms; an area bound on the lattice puts Steiner
# points on cocircular edges): the same files whatever the work-group size.
refinements=("random:-q30" "random:-q30 --refine qm" "lattice:-q30a0.05" "lattice:-q25a0.05 --refine qm")
for index in "${!refinements[@]}"; do
  refinement="${refinements[$index]}"
  input="${refinement%%:*}"
  switches="${refinement#*:}"
  for group in 1 128; do
    # shellcheck disable=SC2086  # switches holds separate arguments
    mesh_in "$work/refine.$index.$group" "$input" $switches --work-group "$group" || continue
    [[ "$group" -eq 1 ]] ||
      same_mesh "$work/refine.$index.1" "$work/refine.$index.$group" "$input" \
        "of '$switches' between work-group sizes 1 and $group"
  done
done

# Quality meshes of PSLGs (segments protected, holes, -c, -D, regional
# areas): the same files whatever the work-group size or the first
# triangulation's construction (with -c the hull edges join the segments of
# the .poly file), and with every buffer from the driver filled with garbage
# first (CLMESH_POISON_BUFFERS), as a GPU's fresh memory may hold: no kernel
# reads what nothing wrote.
pslgs=("pslg/water:-pq30" "pslg/water2:-pcq30" "pslg/water4:-pq25D" "la:-pAq30a")
for index in "${!pslgs[@]}"; do
  case="${pslgs[$index]}"
  path="${case%%:*}"
  input="${path##*/}"
  switches="${case#*:}"
  for group in 1 128 poisoned voronoi fan; do
    dir="pslg.$index.$group"
    mkdir "$dir"
    cp "$source_dir/datasets/$path.poly" "$dir/"
    poison=""
    construction=()
    case "$group" in
      poisoned) poison=0xA5 group=64 ;;
      voronoi | fan) construction=(--construction "$group") group=64 ;;
    esac
    # shellcheck disable=SC2086  # switches holds separate arguments
    (cd "$dir" && CLMESH_POISON_BUFFERS="$poison" "$bin" -QC $switches --work-group "$group" \
      "${construction[@]}" "$input.poly") > "$dir.log" 2>&1 ||
      fail "$input $switches ($dir): $(cat "$dir.log")"
  done
  for ext in node ele poly; do
    for other in 128 poisoned voronoi fan; do
      cmp -s "pslg.$index.1/$input.1.$ext" "pslg.$index.$other/$input.1.$ext" ||
        fail "$input.1.$ext of '$switches' differs between runs 1 and $other"
    done
  done
done

# Refining a mesh (-r, with an .area file) under a sizing field: the same
# files whatever the work-group size.
"$bin" -Q lattice.node
python3 - <<'PY'
rows = [l.split() for l in open("lattice.1.ele") if l.strip() and not l.startswith("#")]
with open("lattice.1.area", "w") as out:
    out.write(f"{int(rows[0][0])}\n")
    for r in rows[1:]:
        out.write(f"{r[0]} {0.02 if int(r[0]) % 3 == 0 else -1}\n")
PY
printf '4 2 1 0\n1 -1 -1 0.3\n2 20 -1 0.05\n3 20 20 0.05\n4 -1 20 0.3\n' > bg.node
printf '2 3 0\n1 1 2 3\n2 1 3 4\n' > bg.ele
for group in 1 128; do
  mkdir "refined.$group"
  cp lattice.1.node lattice.1.ele lattice.1.area bg.node bg.ele "refined.$group/"
  (cd "refined.$group" && "$bin" -nQC -rq30a --size-field bg --work-group "$group" lattice.1) \
    > "refined.$group.log" 2>&1 || fail "-rq30a --size-field: $(cat "refined.$group.log")"
done
for ext in node ele neigh; do
  cmp -s "refined.1/lattice.2.$ext" "refined.128/lattice.2.$ext" ||
    fail "lattice.2.$ext of -rq30a --size-field differs between work-group sizes 1 and 128"
done

# Many meshes in one process on PoCL's multi-threaded device, where the
# work-groups of a launch run at once on several threads (a race between them
# shows as meshes that differ; it needs a busy machine to show, as under
# `ctest -j`): a PSLG with a pinch vertex and acute hull corners, -pq20.
if POCL_DEVICES=pthread "$bin" --list-devices > /dev/null 2>&1; then
  mkdir batch
  for k in $(seq -w 1 40); do cp "$source_dir/datasets/pslg/water.poly" "batch/w$k.poly"; done
  POCL_DEVICES=pthread "$bin" -Q --jobs 1 -pq20 batch/w*.poly > batch.log 2>&1 ||
    fail "-pq20 on 40 copies of water.poly (pthread device): $(cat batch.log)"
  distinct=$(for k in $(seq -w 1 40); do cat "batch/w$k.1.node" "batch/w$k.1.ele" |
    grep -v '^#' | md5sum; done | sort -u | wc -l)
  [[ "$distinct" -eq 1 ]] ||
    fail "40 meshings of water.poly -pq20 in one process give $distinct different meshes"
fi

finish determinism.sh
echo "determinism.sh: all checks passed"
