#!/usr/bin/env python3
"""Refining an existing mesh (-r): clmesh against the native Triangle, side by
side on the same inputs, in one run (ratios are what to quote: absolute times
drift on a shared machine).

The input is a Delaunay mesh of N uniform points in the unit square (about
2N triangles; N = 500000 by default, a mesh of 1M triangles), made once by
Triangle (-Q, or clmesh when no Triangle binary exists) and cached in
BUILD/bench/refine-N/, with an .area file that asks for four times the
density in the lower-left quarter of the domain (a quarter of the mean
triangle area there, no bound elsewhere). Each case runs each tool in a
fresh process:

  clmesh    build/clmesh -Q --stats-json F.json -rSWITCHES u.1
            time = seconds.compute (upload to download: the reconstruction of
            the mesh and the refinement; file reading and writing excluded)
  Triangle  triangle-native -VrSWITCHES u.1, time = its report's "Mesh
            reconstruction" + "Quality" milliseconds (file reading and
            writing excluded)

Cases: -ra (the .area bounds), -rq30 (quality only), -rq30a (both); and
-rpq30 of a mesh with holes: Triangle's -pq25 mesh of the coastline of
100000 vertices of scripts/gen_pslg.py (an outline around islands that are
holes), cached in BUILD/bench/refine-coast/, its .poly's segments and holes
read with -p. Peak memory is each process's maximum resident set size (GNU
time's %M). CGAL has no refinement of a given mesh by per-triangle areas, so
it is not run.

Usage: python3 scripts/bench_refine.py [--points 500000] [--build-dir build]
           [--triangle PATH] [--clmesh PATH] [--repeat K] [--markdown FILE.md]

--markdown FILE also writes the table as the refining section of FILE (the
other sections, written by scripts/bench.py, are kept).
"""
import argparse
import glob
import json
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench import ROOT, ToolFailure, machine_line, run_measured, write_markdown  # noqa: E402

CASES = ("ra", "rq30", "rq30a")
COAST_VERTICES = 100000


def read_rows(path):
    rows = []
    with open(path) as f:
        for line in f:
            fields = line.split("#", 1)[0].split()
            if fields:
                rows.append(fields)
    return rows


def write_area_file(stem):
    """stem.area: a quarter of the mean triangle area for the triangles whose
    centroid lies in the lower-left quarter of the bounding box, -1 elsewhere."""
    nodes = read_rows(stem + ".node")
    count = int(nodes[0][0])
    first = int(nodes[1][0])
    xy = [(float(r[1]), float(r[2])) for r in nodes[1:count + 1]]
    eles = read_rows(stem + ".ele")
    triangles = [[int(v) - first for v in r[1:4]] for r in eles[1:int(eles[0][0]) + 1]]
    xs = [p[0] for p in xy]
    ys = [p[1] for p in xy]
    mid_x, mid_y = (min(xs) + max(xs)) / 2, (min(ys) + max(ys)) / 2
    total = 0.0
    centroids = []
    for a, b, c in triangles:
        (ax, ay), (bx, by), (cx, cy) = xy[a], xy[b], xy[c]
        total += abs((bx - ax) * (cy - ay) - (by - ay) * (cx - ax)) / 2
        centroids.append(((ax + bx + cx) / 3, (ay + by + cy) / 3))
    bound = total / len(triangles) / 4
    with open(stem + ".area", "w") as f:
        f.write(f"{len(triangles)}\n")
        for i, (x, y) in enumerate(centroids):
            f.write(f"{i + first} {bound!r}\n" if x < mid_x and y < mid_y else f"{i + first} -1\n")
    return len(triangles)


def generate_and_mesh(directory, generator, arguments, source, switches, triangle, clmesh):
    """Runs scripts/GENERATOR ARGUMENTS SOURCE in DIRECTORY, then meshes SOURCE
    with SWITCHES by Triangle (or clmesh when no Triangle binary exists)."""
    os.makedirs(directory, exist_ok=True)
    path = os.path.join(directory, source)
    subprocess.run([sys.executable, os.path.join(ROOT, "scripts", generator)] + arguments + [path],
                   check=True)
    tool = triangle if triangle and os.access(triangle, os.X_OK) else clmesh
    subprocess.run([tool, switches, path], check=True)


def make_input(directory, points, triangle, clmesh):
    stem = os.path.join(directory, "u.1")
    if not os.path.exists(stem + ".area"):
        generate_and_mesh(directory, "gen_points.py", ["uniform", str(points)], "u.node", "-Q",
                          triangle, clmesh)
        write_area_file(stem)
    return stem


def make_coast_input(directory, triangle, clmesh):
    """c.1.node, c.1.ele and c.1.poly: a quality mesh (-pq25) of a coastline
    with islands as holes."""
    stem = os.path.join(directory, "c.1")
    if not os.path.exists(stem + ".poly"):
        generate_and_mesh(directory, "gen_pslg.py", ["coast", str(COAST_VERTICES)], "c.poly",
                          "-Qpq25", triangle, clmesh)
    return stem


def clean(stem):
    for path in glob.glob(glob.escape(stem[:-2]) + ".2.*"):
        os.unlink(path)


def run_clmesh(exe, stem, switches, timeout):
    stats = stem + ".stats.json"
    try:
        _, peak, _ = run_measured([exe, "-Q", "--stats-json", stats, "-" + switches, stem], timeout)
        with open(stats) as f:
            data = json.load(f)
        vertices = int(read_rows(stem[:-2] + ".2.node")[0][0])
    finally:
        clean(stem)
    return {"seconds": data["seconds"]["compute"], "vertices": vertices, "peak_mb": peak,
            "device": data.get("device")}


def run_triangle(exe, stem, switches, timeout):
    try:
        stdout, peak, _ = run_measured([exe, "-V" + switches, stem], timeout)
    finally:
        clean(stem)
    ms = {}
    vertices = None
    for line in stdout.splitlines():
        m = re.match(r"\s*(Mesh reconstruction|Quality) milliseconds:\s*(\d+)", line)
        if m:
            ms[m.group(1)] = int(m.group(2))
        m = re.match(r"\s*Mesh vertices:\s*(\d+)", line)
        if m:
            vertices = int(m.group(1))
    if "Mesh reconstruction" not in ms:
        raise ToolFailure("no 'Mesh reconstruction milliseconds' in Triangle's report")
    return {"seconds": sum(ms.values()) / 1000.0, "vertices": vertices, "peak_mb": peak}


def best(k, fn, *args):
    results = [fn(*args) for _ in range(k)]
    out = min(results, key=lambda r: r["seconds"])
    out["peak_mb"] = max(r["peak_mb"] for r in results)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--points", type=int, default=500000)
    ap.add_argument("--build-dir", default=os.path.join(ROOT, "build"))
    ap.add_argument("--clmesh")
    ap.add_argument("--triangle")
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--timeout", type=float, default=1800)
    ap.add_argument("--markdown", metavar="FILE")
    a = ap.parse_args()
    clmesh = a.clmesh or os.path.join(a.build_dir, "clmesh")
    triangle = a.triangle or os.path.join(a.build_dir, "triangle-native")
    stem = make_input(os.path.join(a.build_dir, "bench", f"refine-{a.points}"), a.points, triangle,
                      clmesh)
    triangles = int(read_rows(stem + ".ele")[0][0])
    print(f"Refining a mesh of {a.points} uniform points, {triangles} triangles ({stem}); "
          f".area: 4x the density in the lower-left quarter")
    warm = run_clmesh(clmesh, stem, "rq30a", a.timeout)  # untimed: PoCL builds its kernel variants
    columns = ["case", "clmesh s", "Triangle s", "time ratio", "clmesh vertices",
               "Triangle vertices", "vertex ratio", "clmesh MB", "Triangle MB", "memory ratio"]
    print("  ".join(f"{c:>12}" for c in columns))
    table = ["| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]
    coast = make_coast_input(os.path.join(a.build_dir, "bench", "refine-coast"), triangle, clmesh)
    coast_triangles = int(read_rows(coast + ".ele")[0][0])
    for stem_of_case, case in [(stem, case) for case in CASES] + [(coast, "rpq30")]:
        row = {}
        for name, fn, exe in (("clmesh", run_clmesh, clmesh), ("triangle", run_triangle, triangle)):
            try:
                row[name] = best(a.repeat, fn, exe, stem_of_case, case, a.timeout)
            except ToolFailure as e:
                print(f"  {name} -{case}: {e}")
        c, t = row.get("clmesh"), row.get("triangle")
        if not c or not t:
            continue
        label = f"-{case}" if stem_of_case == stem else f"-{case} (coastline, holes)"
        cells = [label, f"{c['seconds']:.2f}", f"{t['seconds']:.2f}",
                 f"{c['seconds'] / t['seconds']:.2f}", str(c["vertices"]), str(t["vertices"]),
                 f"{c['vertices'] / t['vertices']:.3f}", f"{c['peak_mb']:.0f}",
                 f"{t['peak_mb']:.0f}", f"{c['peak_mb'] / t['peak_mb']:.2f}"]
        print("  ".join(f"{cell:>12}" for cell in cells))
        table.append("| " + " | ".join(cells) + " |")
    if a.markdown:
        notes = [machine_line(warm.get("device")),
                 f"Input: a Delaunay mesh of {a.points} uniform points in the unit square "
                 f"({triangles} triangles, made by Triangle -Q), and an .area file asking for a "
                 "quarter of the mean triangle area in the lower-left quarter of the domain "
                 "(four times the density), no bound elsewhere.  The coastline: Triangle's "
                 f"-pq25 mesh ({coast_triangles} triangles) of scripts/gen_pslg.py coast "
                 f"{COAST_VERTICES} (seed 1: an outline around islands that are holes), "
                 "refined with its .poly's segments and holes (-rpq30).",
                 "clmesh: build/clmesh -Q --stats-json -rSWITCHES u.1, time = seconds.compute "
                 "(the mesh's reconstruction and its refinement; no file reading or writing); "
                 "an untimed run comes first.  Triangle: the native binary (-O3 -march=native, "
                 "build-triangle.sh) with -VrSWITCHES, time = its Mesh reconstruction + Quality "
                 "milliseconds.  CGAL has no refinement of a given mesh by per-triangle areas.",
                 f"Best of {a.repeat} run(s); ratios are clmesh / Triangle.  Peak MB: each "
                 "process's maximum resident set.  With .area bounds clmesh bounds every "
                 "triangle by the given triangle that holds its centroid; Triangle by descent, "
                 "which leaves some triangles above their region's bound."]
        write_markdown(a.markdown, "refine", "Refining a mesh (-r)", table, notes,
                       warm.get("device"))


if __name__ == "__main__":
    main()
