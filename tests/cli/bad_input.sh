#!/usr/bin/env bash
# Bad inputs and switches: a non-zero exit, one 'clmesh: ...' line on stderr
# naming the file (and line), and no file written.
# Usage: bad_input.sh CLMESH_BINARY SOURCE_DIR
set -euo pipefail
source "$(dirname "$0")/common.bash" "$@"
mkdir "$work/data"
cd "$work/data"


printf '4 2 0 0\n1 0 0\n2 1 0\n3 0 1\n4 1 1\n' > good.node
printf '# header below is broken\nabc 2 0 0\n1 0 0\n2 1 0\n3 0 1\n' > header.node
printf '3 2 0 0\n1 0 0\n2 1.0 oops\n3 0 1\n' > word.node
printf '4 2 0 0\n1 0 0\n2 1 0\n\n3 nan 1\n4 1 1\n' > nan.node
printf '2 2 0 0\n1 0 0\n2 1 0\n' > two.node
printf '5 2 0 0\n1 0 0\n2 1 0\n3 0 1\n' > short.node
printf '3 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n' > dim3.node
printf '4 2 0 0\n1 0 0\n2 1 0\n3 0 1\n4 1e300 1\n' > huge.node


expect "missing file" 1 "missing.node" -- missing.node
expect "missing file, no extension" 1 "missing.node" -- missing
expect "malformed header" 1 "header.node:2:" "header" -- -en header.node
expect "malformed header, no extension" 1 "header.node:2:" -- header
expect "non-numeric coordinate" 1 "word.node:3:" "oops" -- word.node
expect "nan coordinate" 1 "nan.node:5:" "nan" -- -z nan.node
expect "fewer than three points" 1 "two.node" "three" -- two.node
expect "fewer vertices than the header says" 1 "short.node:5:" -- short.node
expect "dimension 3" 1 "dim3.node:1:" "dimension" -- dim3.node
expect "coordinate beyond exact arithmetic" 1 "huge.node:5:" "exact arithmetic" -- huge.node
expect "unknown switch" 2 "-x" "-z" -- -zx good.node
expect "unknown long option" 2 "--frobnicate" -- --frobnicate good.node
expect "-r without the mesh's .ele" 1 "good.ele" "cannot open" -- -r good.node
expect "regional areas of a point set" 2 "-a" "needs -p" -- -qa good.node
expect "bad minimum angle" 2 "-q" -- -qx good.node
expect "unknown refinement algorithm" 2 "--refine" "qm" "qmv" -- -q --refine fast good.node
expect "missing .poly input" 1 "good.poly" -- good.poly
expect "missing option value" 2 "--grid" -- good.node --grid
expect "bad option value" 2 "--work-group" -- --work-group zero good.node
expect "standard input as an input file" 2 "'-'" "not an input file" -- -z -
expect "no input file" 2 "input" -- -z

# Input text in messages is quoted with its control bytes escaped: no escape
# sequence reaches the terminal; a line with a NUL byte is an error.
printf '3 2 0 0\n1 0 0\n2 1\033[2J 0\n3 0 1\n' > esc.node
printf '3 2 0 0\n1 0 0\n2 1 0\000\n3 0 1\n' > nul.node
no_escape_byte() {
  if grep -q $'\033' "$work/log/err"; then
    fail "$1: an escape byte reached stderr"
  fi
}
expect "escape sequence in a coordinate" 1 "esc.node:3:" "'1\\x1b[2J'" "not a number" -- esc.node
no_escape_byte "escape sequence in a coordinate"
expect "NUL byte in a coordinate" 1 "nul.node:3:" "NUL byte" -- nul.node
expect "escape sequence in a switch" 2 "unknown switch -\\x1b" "'-z\\x1b[2J'" \
  -- $'-z\033[2J' good.node
no_escape_byte "escape sequence in a switch"
expect "escape sequence in a file name" 1 "bad\\x1b[1m.node" "cannot open" -- $'bad\033[1m.node'
no_escape_byte "escape sequence in a file name"

# Endless or huge inputs are read as they are parsed and stop at their first
# bad line, within seconds, without reserving what a header claims.
ln -s /dev/zero zero.node
ln -s /dev/urandom random.node
mkfifo endless.node
yes > endless.node &
yes_pid=$!
printf '2000000000 2 0 0\n1 0 0\n2 1 0\n3 0 1\n' > many.node
printf '1000000000000 2 0 0\n1 0 0\n2 1 0\n3 0 1\n' > more.node
expect_seconds=20
expect "/dev/zero as input" 1 "zero.node:1:" "NUL byte" -- zero.node
expect "/dev/urandom as input" 1 "random.node:" -- random.node
expect "a FIFO fed by yes" 1 "endless.node:1:" "malformed header: 'y'" -- endless.node
expect "a huge vertex count, 3 vertices" 1 "many.node:5:" "after 3 of 2000000000 vertices" \
  -- many.node
expect "a vertex count beyond 2^31" 1 "more.node:1:" "vertex count" -- more.node
unset expect_seconds
kill "$yes_pid" 2> /dev/null || true
wait "$yes_pid" 2> /dev/null || true
rm zero.node random.node endless.node many.node more.node

# Outputs are all or nothing: an output name taken by a directory, or in a
# folder that does not exist, fails the run, which leaves no new file and
# changes no existing one.
mkdir good.1.ele
expect "output name taken by a directory" 1 "good.1.ele" "directory" -- good.node
printf 'old\n' > good.1.node
expect "a directory among the outputs, an old file" 1 "good.1.ele" -- -en good.node
[[ "$(cat good.1.node)" == "old" ]] || fail "a failed run changed good.1.node"
rm good.1.node
rmdir good.1.ele
expect "output in a missing folder" 1 "no-such-folder/stats.json" -- \
  --stats-json no-such-folder/stats.json good.node

finish bad_input.sh
echo "bad_input.sh: all checks passed"
