#!/usr/bin/env bash
# Checks clmesh on a GPU's OpenCL against PoCL on the same machine: lists the
# devices, meshes every input of datasets/ (its PSLGs at -pq30 -pcq30 -pq20,
# its point sets plain and at -q30) on both and compares the files, then
# runs the test suite on the GPU; before that, A.poly -pcq30 -C as built,
# unoptimised (-cl-opt-disable) and without the predicate check. Between the
# two, the PSLGs of datasets/pslg/ -pq30 as one batch with CLMESH_PROFILE=1:
# what the GPU's kernels and the host's calls into its driver cost. NVIDIA's
# driver library is registered as an ICD when it is found and no ICD names it
# yet (as root).
#   bash scripts/gpu-check.sh [BUILD_DIR] [OUT_DIR]
# Needs a built BUILD_DIR (default build/); writes OUT_DIR/summary.txt and
# the per-run logs (default: a temporary folder, printed at the end).
# The meshes part runs GPU_CHECK_JOBS (default 8) inputs at once.
# GPU_CHECK_PARTS picks the parts, in this order (default: all of them):
# "diagnosis meshes profile batch tests". batch times 200 small coastlines
# (-pq30) and 200 point sets of 2000 points: the default workers (one on a
# GPU, meshing on several streams) against --streams 1 (in its worker, and
# with --jobs 1 in the clmesh process), --streams 16, --jobs 8 (and --pack
# for the point sets), the files of the default and of --streams 1 compared;
# then with no device named (PoCL's CPU device takes them; the files
# compared), with slabs (CLMESH_SLABS=on), and the single-group kernels
# of small meshes at work-groups of 64 (the default), 128 and 256
# (CLMESH_WORK_GROUP); against the native Triangle once per file when
# tools/build-triangle.sh's binary is at BUILD_DIR/triangle-native.
set -uo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="$(cd "${1:-$root/build}" && pwd)"
out="${2:-$(mktemp -d)}"
mkdir -p "$out"
out="$(cd "$out" && pwd)"
clmesh="$build/clmesh"
parts=" ${GPU_CHECK_PARTS:-diagnosis meshes profile batch tests} "
part() { [[ "$parts" == *" $1 "* ]]; }

nvidia=$(ls /usr/local/nvidia/lib64/libnvidia-opencl.so.1 /usr/lib/x86_64-linux-gnu/libnvidia-opencl.so.1 \
  /usr/lib/libnvidia-opencl.so.1 2>/dev/null | head -1)
if [[ -n "$nvidia" ]] && ! grep -qs nvidia /etc/OpenCL/vendors/*.icd && [[ -w /etc ]]; then
  mkdir -p /etc/OpenCL/vendors && echo "$nvidia" > /etc/OpenCL/vendors/nvidia.icd
  export LD_LIBRARY_PATH="$(dirname "$nvidia")${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
fi
"$clmesh" --list-devices | tee "$out/devices.txt"
# The machine's kernel and driver: a sandboxed kernel (gVisor) passes each
# call into the GPU's driver through a proxy, which small meshes feel.
{ uname -sr; nvidia-smi --query-gpu=name,driver_version --format=csv,noheader 2> /dev/null; } |
  tee -a "$out/summary.txt"
gpu="${CLMESH_GPU:-NVIDIA}"
grep -qi "$gpu" "$out/devices.txt" || { echo "gpu-check.sh: no device matches '$gpu'" >&2; exit 1; }
cpu=Portable
grep -q "$cpu" "$out/devices.txt" || cpu=""

# mesh DEVICE NAME INPUT SWITCHES: meshes INPUT in out/NAME/, status in out/NAME.status.
mesh() {
  local device="$1" name="$2" input="$3" switches="$4" status=0
  mkdir -p "$out/$name"
  cp "$input" "$out/$name/"
  # shellcheck disable=SC2086  # switches holds separate arguments
  (cd "$out/$name" && timeout 120 "$clmesh" -Q --device "$device" $switches "$(basename "$input")") \
    > "$out/$name.log" 2>&1 || status=$?
  echo "$status" > "$out/$name.status"
}

# First, one input three ways on the GPU (docs/reference.md, "Checking a GPU"):
# as built, unoptimised, and without the predicate check; -C checks each mesh.
part diagnosis && for way in built "CLMESH_BUILD_OPTIONS=-cl-opt-disable" "CLMESH_PREDICATE_CHECK=off"; do
  status=0
  mkdir -p "$out/diagnosis" && cp "$root/datasets/A.poly" "$out/diagnosis/"
  # shellcheck disable=SC2046  # $way is one assignment or none
  (cd "$out/diagnosis" && env $([[ $way == built ]] || echo "$way") \
    timeout 300 "$clmesh" -Q -C -pcq30 --device "$gpu" A.poly) > "$out/diagnosis/$way.log" 2>&1 ||
    status=$?
  echo "A.poly -pcq30 -C on '$gpu', $way: exit status $status $(head -c 200 "$out/diagnosis/$way.log")" |
    tee -a "$out/summary.txt"
  rm -f "$out/diagnosis/A.1."*
done

# Every input of datasets/ on the GPU and on PoCL, GPU_CHECK_JOBS (default 8)
# inputs at once, then the files compared.
same=0 differ=0 failed=0 runs=0
names=() bases=() inputs=() switch_sets=()
if part meshes; then
  for input in "$root"/datasets/*.poly "$root"/datasets/pslg/*.poly "$root"/datasets/*.node; do
    base="$(basename "${input%.*}")"
    case "$input" in *.poly) sets=("-pq30" "-pcq30" "-pq20") ;; *) sets=("" "-q30") ;; esac
    for switches in "${sets[@]}"; do
      name="$base${switches:-.plain}"
      names+=("$name") bases+=("$base") inputs+=("$(basename "$input")") switch_sets+=("$switches")
      while (($(jobs -rp | wc -l) >= ${GPU_CHECK_JOBS:-8})); do
        wait -n
      done
      (mesh "$gpu" "gpu/$name" "$input" "$switches"
        if [[ -n "$cpu" && "$(cat "$out/gpu/$name.status")" == 0 ]]; then
          mesh "$cpu" "cpu/$name" "$input" "$switches"
        fi) &
    done
  done
  wait
fi
for i in "${!names[@]}"; do
  name="${names[$i]}" base="${bases[$i]}" switches="${switch_sets[$i]}"
  runs=$((runs + 1))
  if [[ "$(cat "$out/gpu/$name.status")" != 0 ]]; then
    failed=$((failed + 1))
    echo "FAILED on the GPU: $base $switches: $(head -c 300 "$out/gpu/$name.log")" >> "$out/summary.txt"
    continue
  fi
  [[ -n "$cpu" ]] || continue
  # The outputs: every file of the run's folder but the input (name.1.* or,
  # for an input name.1, name.2.*), comments left out.
  outputs() { find "$1" -type f ! -name "$2" | sort | xargs cat | grep -v '^#'; }
  if [[ -n "$(find "$out/gpu/$name" -type f ! -name "${inputs[$i]}")" ]] &&
    diff -q <(outputs "$out/gpu/$name" "${inputs[$i]}") \
      <(outputs "$out/cpu/$name" "${inputs[$i]}") > /dev/null; then
    same=$((same + 1))
  else
    differ=$((differ + 1))
    echo "DIFFERS from PoCL: $base $switches" >> "$out/summary.txt"
  fi
done
part meshes &&
  echo "meshes: $runs runs on '$gpu': $failed failed; against PoCL $same the same, $differ differ" |
  tee -a "$out/summary.txt"

# Where small inputs' time goes on the GPU: one worker, every kernel waited
# for; the host's calls (blocking reads, buffers and kernels made) go to the summary.
if part profile; then
  mkdir -p "$out/profile"
  cp "$root"/datasets/pslg/*.poly "$out/profile/"
  start=$(date +%s.%N)
  (cd "$out/profile" && CLMESH_PROFILE=1 CLMESH_DEVICE="$gpu" timeout 300 "$clmesh" -Q -pq30 \
    --jobs 1 ./*.poly) > "$out/profile.txt" 2>&1
  echo "profile of $(ls "$root"/datasets/pslg/*.poly | wc -l) PSLGs -pq30 on '$gpu' (profile.txt)," \
    "$(awk "BEGIN { printf \"%.2f\", $(date +%s.%N) - $start }") s with every launch waited for:" |
    tee -a "$out/summary.txt"
  grep "^host:" "$out/profile.txt" | tee -a "$out/summary.txt"
fi

# seconds COMMAND...: the wall time of COMMAND, in the current folder.
seconds() {
  local start end
  start=$(date +%s.%N)
  "$@" > /dev/null 2>&1
  end=$(date +%s.%N)
  awk "BEGIN { printf \"%.2f\", $end - $start }"
}
# Small inputs in a batch: workers and single-group sizes on the GPU.
if part batch; then
  for kind in pslgs points; do
    dir="$out/batch-$kind"
    mkdir -p "$dir"
    for seed in $(seq 1 200); do
      if [[ $kind == pslgs ]]; then
        python3 "$root/scripts/gen_pslg.py" coast 500 "$dir/in$seed.poly" --seed "$seed"
      else
        python3 "$root/scripts/gen_points.py" uniform 2000 "$dir/in$seed.node" --seed "$seed" 2> /dev/null
      fi
    done
    switches=-Q
    [[ $kind == pslgs ]] && switches=-Qpq30
    # Untimed first runs build the programs on the GPU and on PoCL (with no
    # device named, small inputs go to PoCL): a machine's first build takes
    # minutes, which the timings below leave out.
    (cd "$dir" && ls in* > list.txt && CLMESH_DEVICE="$gpu" "$clmesh" $switches in1.* > /dev/null
      (unset CLMESH_DEVICE; "$clmesh" $switches --batch list.txt > /dev/null 2>&1)
      rm -f ./*.1.*
      line="batch of 200 $kind $switches on '$gpu':"
      packs=""
      [[ $kind == points ]] && packs="--pack"
      for jobs in "" "--streams 1" "--jobs 1 --streams 1" "--streams 16" "--jobs 8" $packs; do
        # shellcheck disable=SC2086  # $jobs is one option and its value, or none
        line+=" ${jobs:-default workers} $(CLMESH_DEVICE="$gpu" seconds "$clmesh" $switches $jobs --batch list.txt) s;"
        [[ -z $jobs ]] && cat ./*.1.* | md5sum > streams.md5
        if [[ $jobs == "--streams 1" ]]; then
          cmp -s streams.md5 <(cat ./*.1.* | md5sum) && line+=" (the same files)" ||
            line+=" (OTHER FILES than the default's)"
        fi
      done
      line+=" no device named (small inputs on PoCL's CPU device) $(unset CLMESH_DEVICE; seconds "$clmesh" $switches --batch list.txt) s"
      cmp -s streams.md5 <(cat ./*.1.* | md5sum) && line+=" (the same files);" ||
        line+=" (OTHER FILES than the default's);"
      line+=" CLMESH_SLABS=on $(CLMESH_DEVICE="$gpu" CLMESH_SLABS=on seconds "$clmesh" $switches --batch list.txt) s;"
      for group in 128 256; do
        line+=" CLMESH_WORK_GROUP=$group $(CLMESH_DEVICE="$gpu" CLMESH_WORK_GROUP=$group seconds "$clmesh" $switches --batch list.txt) s;"
      done
      if [[ -x "$build/triangle-native" ]]; then
        rm -f ./*.1.*
        line+=" Triangle once per file $(seconds bash -c "for f in in*.*; do '$build/triangle-native' $switches \$f; done") s"
      fi
      echo "$line") | tee -a "$out/summary.txt"
  done
fi

if part tests && [[ -x "$build/tests/clmesh_tests" ]]; then
  (cd "$build/tests" && CLMESH_DEVICE="$gpu" timeout 600 ./clmesh_tests --no-intro) \
    > "$out/tests.txt" 2>&1
  grep -E "^\[doctest\] (test cases|assertions)" "$out/tests.txt" | tee -a "$out/summary.txt"
fi
echo "gpu-check.sh: logs in $out"
