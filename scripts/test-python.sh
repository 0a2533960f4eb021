#!/usr/bin/env bash
# Install the Python package into build/venv and run its tests (python/tests/)
# against the triangle package from PyPI.  scripts/test.sh runs it after ctest.
# The module's CMake build stays in build/python, so later runs only rebuild
# what changed.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

venv=build/venv
if [[ ! -x $venv/bin/python ]]; then
  python3 -m venv "$venv"
fi
pip=("$venv/bin/python" -m pip --disable-pip-version-check -q)
# The build backend and the test dependencies, installed once: the build runs
# without isolation so that its paths stay the same from run to run.
"${pip[@]}" install scikit-build-core nanobind ninja numpy pytest triangle
CMAKE_BUILD_PARALLEL_LEVEL="${CMAKE_BUILD_PARALLEL_LEVEL:-$(nproc)}" \
  "${pip[@]}" install --no-build-isolation --config-settings=build-dir=build/python .
# From python/tests, so that the installed package is imported, not the
# sources in python/clmesh (which lack the compiled module).
cd python/tests
exec "../../$venv/bin/python" -m pytest -q -p no:cacheprovider
