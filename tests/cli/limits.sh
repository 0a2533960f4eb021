#!/usr/bin/env bash
# Refinement limits: an area bound (-a) the device cannot hold is refused at
# once, naming the bound, the points it needs and what the device holds; with
# -S below that need the refinement runs to the limit and the warning names
# -S as what stopped it.
# Usage: limits.sh CLMESH_BINARY SOURCE_DIR
set -euo pipefail
source "$(dirname "$0")/common.bash" "$@"
mkdir "$work/data"
cd "$work/data"

printf '4 2 0 0\n1 0 0\n2 1 0\n3 1 1\n4 0 1\n' > square.node

start=$SECONDS
expect "area bound far below the domain's area" 2 "-a1e-30" "~5e29 points" "(area 1)" \
  "device's memory holds" -- -a1e-30 square.node
expect "area bound with an angle bound" 2 "-a1e-9" "~5e8 points" -- -q30a1e-9 square.node
expect "-S beyond what the device holds" 2 "-a1e-9" "-S1000000000000" -- -a1e-9S1e12 square.node
[[ $((SECONDS - start)) -le 30 ]] || fail "the refusals took $((SECONDS - start)) s, wanted seconds"

# -S caps the points far below the area bound's need: refined to the cap, and
# the warning says the Steiner point limit stopped it.
status=0
"$bin" -QCa1e-9S100 --stats-json capped.json square.node 2> err.txt || status=$?
[[ "$status" -eq 0 ]] || fail "-a1e-9S100 exited with $status: $(cat err.txt)"
grep -q "Steiner point limit (-S100)" err.txt || fail "-a1e-9S100: warning lacks -S100: $(cat err.txt)"
[[ "$(wc -l < err.txt)" -eq 1 ]] || fail "-a1e-9S100: wanted one warning line: $(cat err.txt)"
read -r vertices _ < square.1.node
[[ "$vertices" -eq 104 ]] || fail "-a1e-9S100: $vertices vertices, wanted 104"
python3 - capped.json <<'PY' || fail "-a1e-9S100: stats wrong: $(cat capped.json)"
import json, sys
r = json.load(open(sys.argv[1]))["refinement"]
assert r["stop_reason"] == "steiner_limit" and r["steiner_points"] == 100, r
assert r["area_bound_points"] == 5e8, r
PY

finish limits.sh
echo "limits.sh: all checks passed"
