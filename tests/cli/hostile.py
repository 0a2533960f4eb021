#!/usr/bin/env python3
"""Hostile inputs for quality meshing (called by hostile.sh).

PSLGs, from fixed seeds, seven kinds in turn: fans of segments meeting at
angles down to 1e-4 degrees, crossing segments, runs of segments collinear
to 1e-13, vertices on segments and duplicates, rings with holes and a sliver
spike, cocircular rings around a lattice, and combs of teeth down to 1e-7
wide; each at a scale from 1e-9 to 1e7 and an offset up to 1e7. Each is
meshed with -pq30, -pcq25, -pq33, -pYq30, -pq30S50 and -pq25a (a twentieth
of its bounding box's area), and the -pq30 mesh refined again with -rpq33
(its segments and holes from its .poly). (-D is left out: at 1e-9 around 12345 the
rounding of split points can leave a triangle that no split mends, which
clmesh reports and -C then refuses.)

Point sets, six kinds in turn: lattices, a cocircular ring around its
centre, clusters 1e-6 wide, near-duplicates 1e-15 and 1e-12 apart, collinear
runs with two points off the line, and concentric rings; at scales from 1e-8
to 1e6 and offsets up to 1e7. Each is meshed with -q30, -q33, -Dq25 and
--refine qm -q30, and the -q30 mesh refined again with -rq33.

Every run has -QC. It must either exit 0 (the mesh passed -C) or exit 1 or
2 with exactly one stderr line starting 'clmesh: ' and no output file;
never a signal, never a timeout.

Usage: hostile.py CLMESH_BINARY WORK_DIR
Environment: CLMESH_HOSTILE_SEEDS (default 14: seeds 1..N of each family).
"""
import math
import os
import random
import subprocess
import sys

TIMEOUT_S = 60
PSLG_SWITCHES = ["-pq30", "-pcq25", "-pq33", "-pYq30", "-pq30S50", "-pq25a"]
POINT_SWITCHES = [["-q30"], ["-q33"], ["-Dq25"], ["-q30", "--refine", "qm"]]


def generate_pslg(seed):
    """(points, segments, holes) of hostile PSLG number `seed`."""
    r = random.Random(seed)
    kind = seed % 7
    scale = r.choice([1.0, 1e-9, 1e7, 1.0, 3.7e-3])
    offset = r.choice([0.0, 0.0, 1e7, -3e5, 12345.678])
    points, segments, holes = [], [], []

    def point(x, y):
        points.append((offset + x * scale, offset + y * scale))
        return len(points) - 1

    if kind == 0:  # a fan of segments at tiny angles from one vertex
        centre = point(0, 0)
        step = r.choice([1e-2, 1e-4, 0.5, 3.0]) * math.pi / 180
        for k in range(r.randint(3, 12)):
            length = r.uniform(0.5, 2)
            segments.append((centre, point(math.cos(k * step) * length,
                                           math.sin(k * step) * length)))
    elif kind == 1:  # segments crossing at random
        for _ in range(r.randint(3, 40)):
            segments.append((point(r.random(), r.random()), point(r.random(), r.random())))
    elif kind == 2:  # a run of nearly collinear segments in a box
        box = [point(0, 0), point(1, 0), point(1, 1), point(0, 1)]
        segments += [(box[i], box[(i + 1) % 4]) for i in range(4)]
        previous = point(0.1, 0.5)
        for i in range(1, r.randint(5, 60)):
            current = point(0.1 + 0.8 * i / 60, 0.5 + r.choice([0, 1e-12, -1e-13, 1e-9]))
            segments.append((previous, current))
            previous = current
    elif kind == 3:  # vertices on a segment, duplicates, segments from them
        a, b, c = point(0, 0), point(1, 1), point(1, 0)
        segments += [(a, b), (a, c), (b, c)]
        for _ in range(r.randint(1, 20)):
            t = r.random()
            v = point(t, t)
            if r.random() < 0.5:
                point(t, t)
            if r.random() < 0.5:
                segments.append((v, point(t + r.uniform(-0.3, 0.3), t - 0.2)))
    elif kind == 4:  # a jagged ring around a hole, with a sliver spike
        n = r.randint(5, 40)
        ring = [point(math.cos(2 * math.pi * k / n) * (1 + r.uniform(-0.3, 0.3)),
                      math.sin(2 * math.pi * k / n) * (1 + r.uniform(-0.3, 0.3)))
                for k in range(n)]
        segments += [(ring[k], ring[(k + 1) % n]) for k in range(n)]
        m = r.randint(3, 8)
        inner = [point(0.2 * math.cos(2 * math.pi * k / m), 0.2 * math.sin(2 * math.pi * k / m))
                 for k in range(m)]
        segments += [(inner[k], inner[(k + 1) % m]) for k in range(m)]
        holes.append((offset, offset))
        segments.append((ring[0], point(0.9, 1e-6)))
    elif kind == 5:  # a cocircular ring of segments around a lattice
        n = r.randint(8, 64)
        ring = [point(math.cos(2 * math.pi * k / n), math.sin(2 * math.pi * k / n))
                for k in range(n)]
        segments += [(ring[k], ring[(k + 1) % n]) for k in range(n)]
        for i in range(-3, 4):
            for j in range(-3, 4):
                point(i / 4, j / 4)
    else:  # a comb of thin teeth
        teeth = r.randint(3, 30)
        segments.append((point(0, 0), point(1, 0)))
        for k in range(teeth):
            x = (k + 0.5) / teeth
            segments.append((point(x, 0),
                             point(x + r.choice([0, 1e-7, 1e-3]), r.uniform(0.1, 1))))
    return points, segments, holes


def write_poly(path, points, segments, holes):
    with open(path, "w") as f:
        f.write(f"{len(points)} 2 0 1\n")
        for i, (x, y) in enumerate(points):
            f.write(f"{i + 1} {x!r} {y!r} 0\n")
        f.write(f"{len(segments)} 1\n")
        for i, (a, b) in enumerate(segments):
            f.write(f"{i + 1} {a + 1} {b + 1} {i % 3 + 1}\n")
        f.write(f"{len(holes)}\n")
        for i, (x, y) in enumerate(holes):
            f.write(f"{i + 1} {x!r} {y!r}\n")


def generate_points(seed):
    """The points of hostile point set number `seed`."""
    r = random.Random(seed)
    kind = seed % 6
    scale = r.choice([1.0, 1e-8, 1e6, 2.5e-3])
    offset = r.choice([0.0, 1e7, -123.456, 0.0])
    if kind == 0:
        k = r.randint(3, 30)
        points = [(i, j) for i in range(k) for j in range(k)]
    elif kind == 1:
        n = r.randint(8, 400)
        points = [(math.cos(2 * math.pi * i / n), math.sin(2 * math.pi * i / n))
                  for i in range(n)] + [(0, 0)]
    elif kind == 2:
        centres = [(r.random(), r.random()) for _ in range(r.randint(2, 5))]
        points = [(r.gauss(0, 1e-6) + x, r.gauss(0, 1e-6) + y)
                  for x, y in centres for _ in range(r.randint(5, 30))]
    elif kind == 3:
        base = [(r.random(), r.random()) for _ in range(r.randint(5, 40))]
        points = base + [(x + r.choice([0, 1e-15, 1e-12]), y) for x, y in base[:len(base) // 2]]
    elif kind == 4:
        points = [(t, 0.5 * t + r.choice([0, 0, 1e-13]))
                  for t in [r.random() for _ in range(r.randint(5, 200))]] + [(0.5, 2), (0.2, -1)]
    else:
        n = r.randint(4, 60)
        points = [(math.cos(2 * math.pi * i / n) * ring, math.sin(2 * math.pi * i / n) * ring)
                  for ring in (1, 2, 3, 4) for i in range(n)]
    return [(offset + x * scale, offset + y * scale) for x, y in points]


def write_node(path, points):
    with open(path, "w") as f:
        f.write(f"{len(points)} 2 0 0\n")
        for i, (x, y) in enumerate(points):
            f.write(f"{i + 1} {x!r} {y!r}\n")


class Runs:
    """Runs clmesh on inputs in `work` and counts the runs that end badly."""

    def __init__(self, clmesh, work):
        self.clmesh, self.work = clmesh, work
        self.runs = self.failures = 0

    def run(self, arguments, outputs_of, keep=False):
        """clmesh -QC ARGUMENTS; outputs_of: the prefix of the files a run
        writes (removed after it unless `keep` and the run succeeded).
        Returns whether it exited 0."""
        self.runs += 1
        try:
            done = subprocess.run([self.clmesh, "-QC"] + arguments, cwd=self.work,
                                  capture_output=True, text=True, timeout=TIMEOUT_S)
            status, errors = done.returncode, done.stderr
        except subprocess.TimeoutExpired:
            status, errors = "timeout", ""
        outputs = [f for f in os.listdir(self.work) if f.startswith(outputs_of)]
        lines = [line for line in errors.splitlines() if line.startswith("clmesh: ")]
        if not (status == 0 or (status in (1, 2) and len(lines) == 1 and not outputs)):
            self.failures += 1
            print(f"FAIL: {' '.join(arguments)}: status {status}, outputs {outputs}: "
                  f"{errors.strip()[:400]}")
        if not (keep and status == 0):
            for f in outputs:
                os.unlink(os.path.join(self.work, f))
        return status == 0


def refine_again(runs, work, name, switches):
    """Refines the kept mesh NAME.1 with SWITCHES (which hold -r), then
    removes it."""
    runs.run([switches, name + ".1"], name + ".2.")
    for f in os.listdir(work):
        if f.startswith(name + ".1."):
            os.unlink(os.path.join(work, f))


def main():
    clmesh, work = sys.argv[1], sys.argv[2]
    seeds = int(os.environ.get("CLMESH_HOSTILE_SEEDS", "14"))
    runs = Runs(clmesh, work)
    for seed in range(1, seeds + 1):
        points, segments, holes = generate_pslg(seed)
        name = f"h{seed}"
        write_poly(os.path.join(work, name + ".poly"), points, segments, holes)
        xs, ys = [p[0] for p in points], [p[1] for p in points]
        area = (max(xs) - min(xs)) * (max(ys) - min(ys)) / 20
        for switches in PSLG_SWITCHES:
            if switches.endswith("a"):
                switches += repr(area) if area > 0 else "1"
            meshed = runs.run([switches, name + ".poly"], name + ".1.", keep=switches == "-pq30")
            if meshed and switches == "-pq30":
                refine_again(runs, work, name, "-rpq33")
    for seed in range(1, seeds + 1):
        name = f"p{seed}"
        write_node(os.path.join(work, name + ".node"), generate_points(seed))
        for switches in POINT_SWITCHES:
            meshed = runs.run(switches + [name + ".node"], name + ".1.", keep=switches == ["-q30"])
            if meshed and switches == ["-q30"]:
                refine_again(runs, work, name, "-rq33")
    print(f"hostile inputs: {runs.runs} runs, {runs.failures} failed")
    sys.exit(1 if runs.failures else 0)


if __name__ == "__main__":
    main()
