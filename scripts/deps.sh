#!/usr/bin/env bash
# Install the Debian packages clmesh needs to build, test and benchmark.
# Idempotent: when everything is already installed it prints nothing and
# touches nothing (no apt-get update).  Works as root, or through sudo.
set -euo pipefail

export DEBIAN_FRONTEND=noninteractive

PACKAGES=(
  build-essential
  cmake
  ocl-icd-opencl-dev
  opencl-c-headers
  opencl-clhpp-headers
  pocl-opencl-icd
  libcgal-dev
  doctest-dev
  clinfo
  python3
  python3-venv    # scripts/test-python.sh: a venv for the Python package and its tests
  python3-dev     # the Python headers the module builds against
  time            # GNU time: bench.py measures each tool's own peak memory with it
)

missing=()
for pkg in "${PACKAGES[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null || true)
  if [[ "$status" != "install ok installed" ]]; then
    missing+=("$pkg")
  fi
done

if [[ ${#missing[@]} -eq 0 ]]; then
  exit 0
fi

as_root() {
  if [[ $(id -u) -eq 0 ]]; then
    "$@"
  else
    sudo DEBIAN_FRONTEND=noninteractive "$@"
  fi
}

if [[ $(id -u) -ne 0 ]] && ! command -v sudo >/dev/null 2>&1; then
  echo "deps.sh: missing packages: ${missing[*]}" >&2
  echo "deps.sh: not root and sudo is not available; install them by hand." >&2
  exit 1
fi

echo "deps.sh: installing ${missing[*]}" >&2
as_root apt-get update -qq
as_root apt-get install -y -qq --no-install-recommends "${missing[@]}"
