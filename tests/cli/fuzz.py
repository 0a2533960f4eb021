#!/usr/bin/env python3
"""Fuzz test of clmesh's input handling (called by fuzz.sh).

Mutates the small bundled inputs (datasets/*.node, datasets/*.poly, and the
meshes to refine: one of the .node, .ele and .area files of bbox.1 and ell)
from a fixed seed: truncation at a random byte, byte flips, duplicated, deleted and
swapped lines, odd numbers (1e308, 1e-320, -0, nan, inf, ...), negative and
huge counts, CR/LF changes. Runs clmesh -QC with a few switch sets on each
mutant, under a timeout. Each run must either exit 0 (the mesh passed -C) or
exit 1 or 2 with exactly one stderr line starting 'clmesh: ' and no file
written; never a signal, never a timeout.

Usage: fuzz.py CLMESH_BINARY SOURCE_DIR WORK_DIR
Environment: CLMESH_FUZZ_SEED (default 32), CLMESH_FUZZ_RUNS (default 600),
CLMESH_FUZZ_ONLY (run only the mutant with this number, to reproduce one).
"""
import os
import random
import re
import subprocess
import sys

TIMEOUT_S = 10  # a run's limit; the runs here take well under a second
SMALL_BYTES = 10000  # the inputs mutated: the bundled ones up to this size

ODD_NUMBERS = ["1e308", "-1e308", "1e-320", "-0", "nan", "-nan", "inf", "-inf", "1e400",
               "0x10", "99999999999999999999", "4.9e-324", "1e16", "-1e-7", ""]
ODD_COUNTS = ["-1", "-2147483648", "2147483647", "4294967296", "1e9", "0", "3.5", "+7"]

NUMBER = re.compile(rb"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def lines_of(data):
    return data.split(b"\n")


def truncate(rng, data):
    return data[:rng.randrange(len(data) + 1)], "truncated"


def flip_bytes(rng, data):
    data = bytearray(data)
    for _ in range(rng.randint(1, 3)):
        at = rng.randrange(len(data))
        data[at] = rng.choice([rng.randrange(256), data[at] ^ (1 << rng.randrange(8))])
    return bytes(data), "bytes flipped"


def duplicate_line(rng, data):
    lines = lines_of(data)
    at = rng.randrange(len(lines))
    lines.insert(at, lines[at])
    return b"\n".join(lines), f"line {at + 1} duplicated"


def delete_line(rng, data):
    lines = lines_of(data)
    at = rng.randrange(len(lines))
    del lines[at]
    return b"\n".join(lines), f"line {at + 1} deleted"


def swap_lines(rng, data):
    lines = lines_of(data)
    a, b = rng.randrange(len(lines)), rng.randrange(len(lines))
    lines[a], lines[b] = lines[b], lines[a]
    return b"\n".join(lines), f"lines {a + 1} and {b + 1} swapped"


def odd_number(rng, data):
    numbers = list(NUMBER.finditer(data))
    if not numbers:
        return data, "no number to replace"
    match = rng.choice(numbers)
    odd = rng.choice(ODD_NUMBERS).encode()
    return data[:match.start()] + odd + data[match.end():], f"number at byte {match.start()} -> {odd!r}"


def odd_count(rng, data):
    # The first number of a line that starts with one: the headers' counts
    # among them (the vertex, segment, hole and region headers).
    starts = [m for m in re.finditer(rb"(?m)^[ \t]*(\d+)", data)]
    if not starts:
        return data, "no count to replace"
    match = rng.choice(starts[:1] * 3 + starts)  # the first header more often
    odd = rng.choice(ODD_COUNTS).encode()
    return (data[:match.start(1)] + odd + data[match.end(1):],
            f"count at byte {match.start(1)} -> {odd!r}")


def line_ends(rng, data):
    kind = rng.randrange(4)
    if kind == 0:
        return data.replace(b"\n", b"\r\n"), "CRLF line ends"
    if kind == 1:
        return data.replace(b"\n", b"\r"), "CR line ends"
    if kind == 2:
        return data.rstrip(b"\n"), "no final newline"
    at = rng.randrange(len(data) + 1)
    return data[:at] + b"\r" + data[at:], f"CR inserted at byte {at}"


MUTATIONS = [truncate, flip_bytes, duplicate_line, delete_line, swap_lines, odd_number,
             odd_number, odd_count, odd_count, line_ends]

# -S bounds the refinements: a vertex moved to 1e16 makes the hull a needle
# that quality triangles fill only by the billions (the run then ends when
# the device is full, minutes later).
NODE_SWITCHES = ["", "-qS3000", "-zen", "-jN", "-q25eS3000", "-Ie"]
POLY_SWITCHES = ["-p", "-pc", "-pzen", "-pAO", "-pj", "-pq30S3000", "-pcq25aS3000",
                 "-pAq20DS3000", "-pq30YS3000"]
# Meshes to refine (-r): every sixth mutant is one of their files.
MESHES = ["bbox.1", "ell"]
MESH_SWITCHES = ["-r", "-rq30S3000", "-raS3000", "-rq25a0.05S3000", "-rzenS3000", "-rcDS3000"]

def mutate(rng, data):
    descriptions = []
    for _ in range(rng.choice([1, 1, 2, 3])):
        if not data:
            break
        data, what = rng.choice(MUTATIONS)(rng, data)
        descriptions.append(what)
    return data, "; ".join(descriptions)


def files_in(folder):
    return sorted(os.listdir(folder))


def main():
    binary, source_dir, work = sys.argv[1:4]
    seed = int(os.environ.get("CLMESH_FUZZ_SEED", "32"))
    runs = int(os.environ.get("CLMESH_FUZZ_RUNS", "600"))
    only = os.environ.get("CLMESH_FUZZ_ONLY")
    print(f"fuzz: seed {seed}, {runs} mutants (CLMESH_FUZZ_SEED, CLMESH_FUZZ_RUNS, "
          f"CLMESH_FUZZ_ONLY=N to rerun mutant N)", flush=True)
    datasets = os.path.join(source_dir, "datasets")
    inputs = sorted(name for name in os.listdir(datasets)
                    if name.endswith((".node", ".poly"))
                    and os.path.getsize(os.path.join(datasets, name)) <= SMALL_BYTES)
    rng = random.Random(seed)
    failures = 0
    for number in range(runs):
        if number % 6 == 5:
            base = rng.choice(MESHES)
            files = {base + ext: None for ext in (".node", ".ele", ".area")
                     if os.path.exists(os.path.join(datasets, base + ext))}
            name = rng.choice(sorted(files))
            switches = rng.choice(MESH_SWITCHES)
            target = base
        else:
            name = rng.choice(inputs)
            poly = name.endswith(".poly")
            base = os.path.splitext(name)[0]
            files = {name: None}
            if poly and os.path.exists(os.path.join(datasets, base + ".node")):
                files[base + ".node"] = None  # a .poly without vertices reads it
            switches = None
            target = name
        with open(os.path.join(datasets, name), "rb") as f:
            mutant, what = mutate(rng, f.read())
        if switches is None:
            switches = rng.choice(POLY_SWITCHES if name.endswith(".poly") else NODE_SWITCHES)
        if only is not None and int(only) != number:
            continue
        folder = os.path.join(work, f"m{number}")
        os.mkdir(folder)
        for file in files:
            with open(os.path.join(folder, file), "wb") as g:
                if file == name:
                    g.write(mutant)
                else:
                    with open(os.path.join(datasets, file), "rb") as f:
                        g.write(f.read())
        before = files_in(folder)
        command = [binary, "-QC" + switches.lstrip("-"), target]
        problem = None
        try:
            done = subprocess.run(command, cwd=folder, stdout=subprocess.PIPE,
                                  stderr=subprocess.PIPE, timeout=TIMEOUT_S)
            status, err = done.returncode, done.stderr.decode(errors="replace")
            after = files_in(folder)
            if status < 0 or status >= 128:
                problem = f"killed by a signal (exit status {status})"
            elif status != 0:
                lines = err.split("\n")[:-1] if err.endswith("\n") else err.split("\n")
                if status not in (1, 2):
                    problem = f"exit status {status}"
                elif len(lines) != 1 or not lines[0].startswith("clmesh: "):
                    problem = f"exit status {status} without exactly one 'clmesh: ' line"
                elif after != before:
                    problem = f"exit status {status} but files written: {sorted(set(after) - set(before))}"
        except subprocess.TimeoutExpired:
            status, err = None, ""
            problem = f"no end within {TIMEOUT_S} s"
        if problem:
            print(f"FAIL: mutant {number} of {name} ({what}), "
                  f"clmesh {' '.join(command[1:])}: {problem}")
            print(f"  stderr: {err.strip()!r}")
            print(f"  mutant bytes: {mutant!r}", flush=True)
            failures += 1
        else:
            print(f"ok: mutant {number} of {name} ({what}), {' '.join(command[1:])}: "
                  f"exit {status}{(': ' + err.strip().splitlines()[0]) if err.strip() else ''}",
                  flush=True)
        for leftover in os.listdir(folder):
            os.remove(os.path.join(folder, leftover))
        os.rmdir(folder)
    if failures:
        print(f"fuzz: {failures} failure(s), seed {seed}")
        return 1
    print(f"fuzz: all runs ended as they should, seed {seed}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
