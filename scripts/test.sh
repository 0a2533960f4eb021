#!/usr/bin/env bash
# Build clmesh (Release) and run the whole test suite: ctest, then the Python
# package's tests (scripts/test-python.sh); exits non-zero when either fails.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/deps.sh

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)"

# Tests run serially by default: every test process drives OpenCL on PoCL,
# whose CPU device already spreads each kernel over all cores (and compiles
# kernels with LLVM on all of them).  Running two such processes at once on a
# 2-core machine only oversubscribes the cores and makes per-test timeouts
# flaky, for little gain.  Set CLMESH_TEST_JOBS to override.
status=0
ctest --test-dir build --output-on-failure -j"${CLMESH_TEST_JOBS:-1}" || status=1
# The Python package, against the triangle package from PyPI.
bash scripts/test-python.sh || status=1
exit "$status"
