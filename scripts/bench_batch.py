#!/usr/bin/env python3
"""Batches of small meshes: one clmesh process against the native Triangle run
once per file (as shell batch jobs do) and a loop over the Python `triangle`
package, side by side on the same inputs in one run (quote the ratios:
absolute times drift on a shared machine).

Two batches, each of --count files (default 2000), generated once and cached
in BUILD/bench/batch-*/:
  points  uniform point sets of --points points (default 2000), Delaunay
          triangulation (no switches)
  pslgs   coastlines of about --vertices vertices (default 500; an outline and
          small islands as holes, scripts/gen_pslg.py coast), -pq30

Timed, as wall time from start to exit of everything the batch needs:
  clmesh --batch   build/clmesh -Q SWITCHES --batch LIST: one run, its worker
                   processes (--jobs, by default one a CPU, with the small
                   inputs on PoCL's in-thread device also where a GPU comes
                   first; one with CLMESH_DEVICE naming a GPU, meshing several
                   inputs at once on streams) each setting the device,
                   context and kernels up once
  --jobs 1         the same with one worker meshing one input at a time
  --pack           the point sets in packs, in one process (clmesh --pack; meant
                   for GPUs: a CPU meshes small sets faster one by one)
  Triangle x N     the native binary (build-triangle.sh), one process per
                   file, started one after the other
  Python loop      in one Python process: triangle.triangulate(dict, SWITCHES)
                   for every file, with the reading of each file (numpy) and
                   no writing; only when numpy and triangle import

Also reported: the wall time of one small clmesh run (1000 points) from
process start to exit, with its parts from --stats-json (reading, compute,
writing) and what remains (process start, OpenCL set-up, built kernels).

Usage: python3 scripts/bench_batch.py [--count 2000] [--points 2000]
           [--vertices 500] [--kinds points,pslgs] [--build-dir build]
           [--triangle PATH] [--clmesh PATH] [--python PATH] [--markdown FILE.md]

--kinds measures only the batches named (a device session with little time,
say --kinds pslgs).

--markdown FILE also writes the table as the batch section of FILE (the
other sections are kept).
"""
import argparse
import json
import multiprocessing
import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench import ROOT, write_markdown  # noqa: E402

PYTHON_LOOP = r"""
import sys, time
import numpy as np
import triangle

def rows(path):
    out = []
    for line in open(path):
        fields = line.split('#', 1)[0].split()
        if fields:
            out.append(fields)
    return out

def read(path):
    r = rows(path)
    n = int(r[0][0])
    first = int(r[1][0]) if n else 0
    tri = {'vertices': np.array([[float(x[1]), float(x[2])] for x in r[1:n + 1]])}
    if path.endswith('.poly'):
        m = int(r[n + 1][0])
        tri['segments'] = np.array([[int(x[1]) - first, int(x[2]) - first]
                                    for x in r[n + 2:n + 2 + m]])
        h = int(r[n + 2 + m][0])
        if h:
            tri['holes'] = np.array([[float(x[1]), float(x[2])]
                                     for x in r[n + 3 + m:n + 3 + m + h]])
    return tri

switches, paths = sys.argv[1], sys.argv[2:]
start = time.perf_counter()
for path in paths:
    triangle.triangulate(read(path), switches)
print(time.perf_counter() - start)
"""


def write_input(job):
    kind, size, seed, path = job
    if kind == "points":
        import gen_points
        gen_points.main(["uniform", str(size), path, "--seed", str(seed)])
    else:
        import gen_pslg
        gen_pslg.main(["coast", str(size), path, "--seed", str(seed)])


def generate(directory, kind, count, size):
    """The batch's inputs (scripts/gen_points.py uniform or gen_pslg.py coast,
    seeds 1 to count), written where missing, by a pool of processes."""
    os.makedirs(directory, exist_ok=True)
    ext = ".node" if kind == "points" else ".poly"
    paths = [os.path.join(directory, f"in{i:05d}{ext}") for i in range(count)]
    missing = [(kind, size, i + 1, p) for i, p in enumerate(paths) if not os.path.exists(p)]
    if missing:
        with multiprocessing.Pool() as pool:
            pool.map(write_input, missing, chunksize=16)
    return paths


def clean(directory):
    for name in os.listdir(directory):
        if ".1." in name:
            os.unlink(os.path.join(directory, name))


def wall(cmd, **kwargs):
    start = time.perf_counter()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, **kwargs)
    return time.perf_counter() - start


def python_loop(python, switches, paths):
    probe = subprocess.run([python, "-c", "import numpy, triangle"], capture_output=True)
    if probe.returncode:
        return None
    out = subprocess.run([python, "-c", PYTHON_LOOP, switches] + paths, check=True,
                         capture_output=True, text=True)
    return float(out.stdout.strip().splitlines()[-1])


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--count", type=int, default=2000)
    ap.add_argument("--points", type=int, default=2000)
    ap.add_argument("--vertices", type=int, default=500)
    ap.add_argument("--kinds", default="points,pslgs",
                    help="comma-separated batches to measure: points, pslgs")
    ap.add_argument("--build-dir", default=os.path.join(ROOT, "build"))
    ap.add_argument("--clmesh")
    ap.add_argument("--triangle")
    ap.add_argument("--python", help="a Python with numpy and triangle (default: "
                    "BUILD/venv/bin/python when it exists, else this one)")
    ap.add_argument("--markdown", metavar="FILE")
    a = ap.parse_args()
    venv = os.path.join(a.build_dir, "venv", "bin", "python")
    python = a.python or (venv if os.access(venv, os.X_OK) else sys.executable)
    clmesh = os.path.abspath(a.clmesh or os.path.join(a.build_dir, "clmesh"))
    triangle = os.path.abspath(a.triangle or os.path.join(a.build_dir, "triangle-native"))
    bench = os.path.join(a.build_dir, "bench")
    columns = ["batch", "files", "switches", "clmesh --batch s", "--jobs 1 s", "--pack s",
               "Triangle x N s", "ratio", "Python loop s", "ratio to loop"]
    print("  ".join(f"{c:>16}" for c in columns))
    table = ["| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]
    kinds = a.kinds.split(",")
    unknown = set(kinds) - {"points", "pslgs"}
    if unknown:
        ap.error(f"--kinds: unknown batch {', '.join(sorted(unknown))}")
    for kind, size, switches in (("points", a.points, ""), ("pslgs", a.vertices, "pq30")):
        if kind not in kinds:
            continue
        directory = os.path.join(bench, f"batch-{kind}-{a.count}x{size}")
        paths = generate(directory, kind, a.count, size)
        listing = os.path.join(directory, "list.txt")
        with open(listing, "w") as f:
            f.write("\n".join(os.path.basename(p) for p in paths) + "\n")
        # Untimed, one input each: the programs and libraries come into memory
        # (the first run after a pause paid up to a second more).
        first = os.path.basename(paths[0])
        for tool in (clmesh, triangle):
            subprocess.run([tool, "-Q" + switches, first], check=True, cwd=directory,
                           stdout=subprocess.DEVNULL)
        clean(directory)
        ours = wall([clmesh, "-Q" + switches, "--batch", "list.txt"], cwd=directory)
        clean(directory)
        one_worker = wall([clmesh, "-Q" + switches, "--jobs", "1", "--batch", "list.txt"],
                          cwd=directory)
        clean(directory)
        packed = None
        if kind == "points":
            packed = wall([clmesh, "-Q" + switches, "--pack", "--batch", "list.txt"],
                          cwd=directory)
            clean(directory)
        start = time.perf_counter()
        for p in paths:
            subprocess.run([triangle, "-Q" + switches, os.path.basename(p)], check=True,
                           cwd=directory, stdout=subprocess.DEVNULL)
        theirs = time.perf_counter() - start
        clean(directory)
        loop = python_loop(python, switches, paths)
        row = [kind, str(a.count), "-" + switches if switches else "(none)", f"{ours:.2f}",
               f"{one_worker:.2f}", f"{packed:.2f}" if packed else "-", f"{theirs:.2f}",
               f"{ours / theirs:.2f}",
               f"{loop:.2f}" if loop else "n/a", f"{ours / loop:.2f}" if loop else ""]
        print("  ".join(f"{c:>16}" for c in row))
        table.append("| " + " | ".join(row) + " |")

    # One small run, start to exit, and where its time goes.
    one = os.path.join(bench, "batch-single")
    node = generate(one, "points", 1, 1000)[0]
    clean(one)
    stats = os.path.join(one, "stats.json")
    wall([clmesh, "-Q", "--stats-json", stats, node])  # untimed: the kernel cache
    clean(one)
    total = wall([clmesh, "-Q", "--stats-json", stats, node])
    clean(one)
    with open(stats) as f:
        data = json.load(f)
    seconds = data["seconds"]
    parts = {k: seconds.get(k, 0.0) for k in ("read", "compute", "write")}
    rest = total - sum(parts.values())
    single = (f"One run of 1000 points: {total * 1000:.1f} ms from start to exit: read "
              f"{parts['read'] * 1000:.1f} ms, compute (upload to download) "
              f"{parts['compute'] * 1000:.1f} ms, write {parts['write'] * 1000:.1f} ms; the "
              f"rest (process start, the OpenCL platform and devices, loading the built "
              f"kernels) {rest * 1000:.1f} ms.")
    print("\n" + single)
    if a.markdown:
        notes = [None,
                 f"Inputs: {a.count} uniform point sets of {a.points} points (Delaunay, no "
                 f"switches) and {a.count} coastlines of about {a.vertices} vertices "
                 f"(scripts/gen_pslg.py coast: an outline and islands as holes, -pq30).",
                 "Wall time from start to exit of everything the batch needs, reading and "
                 "writing the files included, after one untimed run of clmesh and of "
                 "Triangle on the first input.  clmesh: one run of build/clmesh -Q SWITCHES "
                 "--batch LIST with its default workers (one process a CPU; one on a GPU "
                 "named, there on several streams), and with --jobs 1 (one input at a time), and the point sets with --pack (packs of small meshes in "
                 "one process, for GPUs).  Triangle x N: the native binary (-O3 -march=native, "
                 "build-triangle.sh) run once per file, one after the other.  Python loop: "
                 "triangle.triangulate (the PyPI wheel) on each file's arrays in one Python "
                 "process, reading included, no writing.  Ratios: clmesh --batch over the "
                 "other.",
                 single]
        write_markdown(a.markdown, "batch", "Batches of small meshes", table, notes,
                       data.get("device"))


if __name__ == "__main__":
    main()
