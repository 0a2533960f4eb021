# Shared by the command-line tests (sourced; not a test itself).
# Usage in a test: source "$(dirname "$0")/common.bash" "$@"
# Sets bin (absolute path of clmesh), source_dir, work (a fresh temporary
# folder, removed at exit, holding log/), fail() to record a failure and
# finish() to report them.
bin="$(cd "$(dirname "$1")" && pwd)/$(basename "$1")"
source_dir="$(cd "${2:-.}" && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mkdir "$work/log"

failures=0
fail() {
  echo "FAIL: $*" >&2
  failures=$((failures + 1))
}

# run ARGS...: runs clmesh ARGS in the current folder (stdout.txt, stderr.txt)
# and records a failure when it exits non-zero.
run() {
  local status=0
  "$bin" "$@" > stdout.txt 2> stderr.txt || status=$?
  if [[ "$status" -ne 0 ]]; then
    fail "clmesh $* exited with $status: $(cat stderr.txt)"
  fi
  return 0
}

# finish NAME: exits 1 when any check failed.
finish() {
  if [[ "$failures" -ne 0 ]]; then
    echo "$1: $failures check(s) failed" >&2
    exit 1
  fi
}

# expect WHAT STATUS WORDS... -- ARGS...: runs clmesh ARGS, wants exit STATUS,
# a single stderr line starting with 'clmesh: ' and holding every WORD, and
# the data directory unchanged. The run is stopped after $expect_seconds
# seconds (default 300), which gives the status 124.
expect() {
  local what="$1" want_status="$2"
  shift 2
  local words=()
  while [[ "$1" != "--" ]]; do
    words+=("$1")
    shift
  done
  shift
  local before after status=0
  before="$(ls -A | sort)"
  timeout "${expect_seconds:-300}" "$bin" "$@" > "$work/log/out" 2> "$work/log/err" || status=$?
  after="$(ls -A | sort)"
  local err
  err="$(cat "$work/log/err")"
  if [[ "$status" -ne "$want_status" ]]; then
    fail "$what: exit status $status, wanted $want_status (stderr: $err)"
  fi
  if [[ "$(wc -l < "$work/log/err")" -ne 1 ]]; then
    fail "$what: wanted exactly one line on stderr, got: $err"
  fi
  if [[ "$err" != "clmesh: "* ]]; then
    fail "$what: message does not start with 'clmesh: ': $err"
  fi
  local word
  for word in "${words[@]}"; do
    if [[ "$err" != *"$word"* ]]; then
      fail "$what: message lacks '$word': $err"
    fi
  done
  if [[ "$before" != "$after" ]]; then
    fail "$what: files changed in the directory: $(diff <(echo "$before") <(echo "$after") | tr '\n' ' ')"
  fi
}
