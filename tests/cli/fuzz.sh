#!/usr/bin/env bash
# Fuzz test: mutants of the small bundled inputs, from a fixed seed, end in a
# checked mesh or in one 'clmesh: ' line with no file written; never a signal
# or a hang (tests/cli/fuzz.py says how; its output keeps a failing mutant).
# Usage: fuzz.sh CLMESH_BINARY SOURCE_DIR
set -euo pipefail
source "$(dirname "$0")/common.bash" "$@"
python3 "$(dirname "$0")/fuzz.py" "$bin" "$source_dir" "$work"
