#!/usr/bin/env bash
# Hostile PSLGs and point sets (tiny angles, crossings, near-collinear runs,
# duplicates, slivers, cocircular rings, extreme scales and offsets) meshed
# to quality end in a checked mesh or in one 'clmesh: ' line with no file
# written; never a signal or a hang (tests/cli/hostile.py says how).
# Usage: hostile.sh CLMESH_BINARY SOURCE_DIR
set -euo pipefail
source "$(dirname "$0")/common.bash" "$@"
python3 "$(dirname "$0")/hostile.py" "$bin" "$work"
