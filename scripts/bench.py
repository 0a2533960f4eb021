#!/usr/bin/env python3
"""Benchmark clmesh against Triangle and CGAL on the thesis point distributions.

For each distribution and size the input is generated once (cached in
build/bench/) and then three tools triangulate it, each in a fresh process:

  clmesh    build/clmesh -Q --stats-json F.json INPUT.node
            time = seconds.compute from the stats JSON (plus the per-phase times)
  Triangle  build/triangle-native -NEP INPUT.node when that binary exists
            (Shewchuk's triangle.c built by /work/shared/tools/build-triangle.sh,
            or any binary given with --triangle PATH): time = its own report,
            Delaunay + Segment + Hole + Quality milliseconds, file reading and
            writing excluded.  Otherwise (or with --triangle python) the PyPI
            package `triangle` (installed with pip if missing) in a child
            Python that loads the points first and times only
            triangle.triangulate({'vertices': pts}, '')
  CGAL      build/cgal_bench dt INPUT.node  (Delaunay_triangulation_2, Epick,
            range insert; times only the construction)

Peak memory is each tool process's maximum resident set size, from GNU time's
%M when /usr/bin/time exists, otherwise from os.wait4's ru_maxrss.  With the
PyPI package, Triangle's figure includes the Python interpreter, numpy and the
loaded point array.  --repeat K keeps the best time of K runs (and the largest
peak memory).  With --repeat 1, clmesh first runs once untimed on each input:
PoCL compiles a kernel's variant at its first launch of a new shape, and that
compilation would otherwise land in the compute time after any kernel change.  A tool that fails gets 'fail' in its cells; the reasons are
listed under the table.

With --cdt the inputs are planar straight-line graphs instead (.poly files,
N uniform points in the unit square and N/10 segments, cached in build/bench/)
and each tool builds the constrained Delaunay triangulation of the whole convex
hull:

  clmesh    build/clmesh -pc -Q --stats-json F.json INPUT.poly
            time = seconds.compute (the constraint phases are in the phases column)
  Triangle  triangle-native -NEPpc INPUT.poly (its segment recovery: the
            Segment and Hole milliseconds), or with the PyPI package
            triangle.triangulate({'vertices': pts, 'segments': segs}, 'pc'),
            timing only that call
  CGAL      build/cgal_bench cdt INPUT.poly  (Constrained_Delaunay_triangulation_2,
            Epick: range insert of the points, then insert_constraint per segment)

Two kinds of segments (--variants):
  short  edges of the Delaunay triangulation (Triangle's) of a random quarter
         of the points, N/10 of them picked at random: non-crossing because they
         are edges of one planar triangulation, about two point spacings long,
         and mostly not Delaunay edges of all the points (the other points fall
         in their circumcircles), so each crosses a few triangles.
  long   the square is cut into N/100 horizontal strips; in each, 11 of its
         points (about 100) are joined left to right by an x-monotone chain of
         10 segments.  Segments of one chain have disjoint x ranges but for the
         shared endpoint, and the points of a strip all lie strictly below those
         of the next (strip = floor(y * strips), monotone in y), so no two
         segments cross.  Each is about 1/11 of the square long: some 30 (100k
         points) to 90 (1M) point spacings, crossing that many triangles or more.

With --quality the same point sets (sizes default to 100000 in this mode,
10000 with --quick) are turned into quality meshes of their convex hull, once
per minimum angle in --angles (default 20,30 degrees), by four mesh generators:

  QM-V      build/clmesh --refine qmv -Q -qANGLE --stats-json F.json INPUT.node
  QM        build/clmesh --refine qm -Q -qANGLE --stats-json F.json INPUT.node
            (--algorithms qmv,qm picks which of the two run; default both)
            time = seconds.compute; vertices = input points + the
            refinement's steiner_points.  The last column gives the first
            variant's seconds in the three steps of each iteration (phases
            offcenter_insertion / missing_point_insertion / flipflop_deletion,
            plus the flipping phase; the initial Delaunay triangulation's
            missing point insertion and flipping are charged to them too),
            step 3's Delaunay (D) and non-Delaunay (ND: flops and 3-1 flips)
            flips, the redundant points it deleted and the points inserted
            again after being deleted (inserted_more_than_once); bad triangles
            left (small hull angles, as Triangle leaves them) are added there
            and listed as warnings.
  Triangle  triangle-native -NEPqANGLE INPUT.node (vertices = its "Mesh
            vertices"), or with the PyPI package
            triangle.triangulate({'vertices': pts}, 'qANGLE'), timing only
            that call; vertices = len(result['vertices'])
  CGAL      build/cgal_bench mesh ANGLE INPUT.node  (Constrained_Delaunay_triangulation_2,
            Epick, the points inserted as a range, the convex hull edges made
            constraints, then refine_Delaunay_mesh_2 with
            Delaunay_mesh_criteria_2(sin^2 ANGLE): times all of that, not the
            file reading; vertices = number_of_vertices().  CGAL guarantees
            termination only up to about 20.7 degrees.)

The time ratios are each clmesh variant's time / Triangle's (below 1: clmesh
is faster), the vertex ratios its vertex count / Triangle's for the same angle
bound (above 1: clmesh inserted more Steiner points).  The table also gives
each clmesh variant's and Triangle's peak resident memory and system CPU
seconds (mostly the kernel zeroing fresh pages: on a virtual machine its cost
per GB drifts from run to run, and it grows with the footprint).  --repeat
works as above.

With --pslg the inputs are large PSLGs made by scripts/gen_pslg.py (cached in
build/bench/), meshed to quality with minimum angle ANGLE (--angles, default 30)
by three tools:

  coast     a fractal closed outline around small closed islands (50 vertices
            each), every island a hole with a seed at its centre; n = all
            vertices (default 100000), about half on the outline; -pqANGLE.
  segments  n points on a jittered grid (default 1000000), n/10 of the cells
            holding a short segment (two points) instead of one point: n/10
            non-crossing segments, well apart; -pcqANGLE (the convex hull).
  square    the unit square, -pqANGLEa(1/n) (default n 1000000): a lattice-like
            mesh, whose in-circle tests are mostly exact cocircular ties; no
            CGAL run (cgal_bench bounds angles only).
  (--kinds picks them; --sizes N,... runs each kind at each N instead of its
  default, --quick at 10000.)

  clmesh    build/clmesh -pqANGLE -Q --stats-json F.json INPUT.poly (or -pcqANGLE),
            time = seconds.compute; first an untimed run with -C (the exact
            check of the output mesh): a failed check fails the tool
  Triangle  triangle-native -PpqANGLE INPUT.poly (or -PpcqANGLE), timed by its
            report; it writes INPUT.1.node/.ele (outside its timing), read back
            for the counts below; the native binary only
  CGAL      build/cgal_bench pslgmesh ANGLE [hull] INPUT.poly
            (refine_Delaunay_mesh_2 with the holes as seeds and
            Delaunay_mesh_criteria_2(b = sin^2 ANGLE): CGAL's b is 1 / (4 B^2) for
            its radius-edge bound B, and sin ANGLE = 1 / (2 B); 'hull' constrains
            the convex hull edges too, for -c)

The table gives each tool's seconds, the ratios clmesh/Triangle and
clmesh/CGAL, each tool's vertices (clmesh's and Triangle's output .node, CGAL's
vertices of faces in the domain) and clmesh's vertex ratio to Triangle, the
triangles with an angle below ANGLE in each output with its smallest angle
(clmesh's and Triangle's computed from their output files by a child Python,
CGAL's by cgal_bench, all as the squared sine of the smallest angle against
sin^2 ANGLE, 1e-9 relative tolerance), and each tool's peak memory.

Usage: python3 scripts/bench.py [--quick] [--sizes 100000,1000000]
           [--dists uniform,grid] [--repeat K] [--markdown FILE.md]
       python3 scripts/bench.py --cdt [--quick] [--sizes ...] [--variants short,long]
       python3 scripts/bench.py --quality [--quick] [--sizes 100000] [--angles 20,30]
           [--dists ...] [--algorithms qmv,qm]
       python3 scripts/bench.py --pslg [--quick] [--sizes ...] [--kinds coast,segments,square]
           [--angles 30]

All modes take --build-dir DIR (default build/: DIR/clmesh, DIR/cgal_bench,
DIR/triangle-native and the cached inputs in DIR/bench/), or the binaries with
--clmesh, --cgal and --triangle.

--markdown FILE (all modes) also writes the table and its notes, with the
command line, the date, the machine (CPU model, cores) and the clmesh git commit
(with -dirty when its code differs from it), as the section of this mode in
FILE; the sections of the other modes already in FILE are kept, so

  python3 scripts/bench.py --markdown docs/benchmarks.md
  python3 scripts/bench.py --quality --markdown docs/benchmarks.md

give one file with both tables.
"""
import argparse
import glob
import json
import os
import platform
import re
import subprocess
import sys
import tempfile
import threading
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DISTS = ("uniform", "gaussian", "disk", "circle", "grid")

# Runs in a child Python: loads a .node file, then times only the triangulation.
TRIANGLE_CHILD = r"""
import json, re, sys, time
import numpy as np
import triangle

def read_node(path):
    # Lean on memory: the text once, then one float array.
    with open(path) as f:
        text = f.read()
    if '#' in text:
        text = re.sub(r'#[^\n]*', '', text)
    first, _, rest = text.lstrip().partition('\n')
    del text
    head = first.split()
    n = int(head[0])
    nattr = int(head[2]) if len(head) > 2 else 0
    nmark = int(head[3]) if len(head) > 3 else 0
    cols = 3 + nattr + nmark
    body = np.fromstring(rest, dtype=np.float64, sep=' ')
    if body.size < n * cols:
        raise SystemExit(f'{path}: expected {n} vertices')
    return np.ascontiguousarray(body[:n * cols].reshape(n, cols)[:, 1:3])

pts = read_node(sys.argv[1])
switches = sys.argv[2] if len(sys.argv) > 2 else ''  # e.g. 'q30' for --quality
t0 = time.perf_counter()
out = triangle.triangulate({'vertices': pts}, switches)
t1 = time.perf_counter()
print(json.dumps({'seconds': t1 - t0, 'triangles': int(len(out['triangles'])),
                  'vertices': int(len(out['vertices']))}))
"""


# Runs in a child Python: loads a .poly file (vertices in it), then times only the CDT.
TRIANGLE_CDT_CHILD = r"""
import json, sys, time
import numpy as np
import triangle

def read_poly(path):
    lines = []
    with open(path) as f:
        for line in f:
            line = line.split('#', 1)[0].split()
            if line:
                lines.append(line)
    n = int(lines[0][0])
    ids = np.array([float(l[0]) for l in lines[1:n + 1]])
    base = int(ids[0]) if n else 0
    pts = np.array([[float(l[1]), float(l[2])] for l in lines[1:n + 1]], dtype=np.float64)
    m = int(lines[n + 1][0])
    segs = np.array([[int(l[1]) - base, int(l[2]) - base] for l in lines[n + 2:n + 2 + m]],
                    dtype=np.int32).reshape(-1, 2)
    return pts, segs

pts, segs = read_poly(sys.argv[1])
# The Delaunay triangulation of the points alone first: Triangle's -p builds
# it the same way before it recovers the segments, so the difference of the
# two times is its segment recovery.
t0 = time.perf_counter()
triangle.triangulate({'vertices': pts}, '')
t1 = time.perf_counter()
out = triangle.triangulate({'vertices': pts, 'segments': segs}, 'pc')
t2 = time.perf_counter()
print(json.dumps({'seconds': t2 - t1, 'dt_seconds': t1 - t0,
                  'triangles': int(len(out['triangles'])),
                  'vertices': int(len(out['vertices']))}))
"""

# Runs in a child Python: writes a PSLG as a .poly (see the module docstring).
PSLG_GENERATOR = r"""
import sys
import numpy as np

variant, n, path, seed = sys.argv[1], int(sys.argv[2]), sys.argv[3], int(sys.argv[4])
m = n // 10
rng = np.random.default_rng(seed)
pts = rng.random((n, 2))
if variant == 'short':
    import triangle
    subset = rng.choice(n, size=max(3, n // 4), replace=False)
    out = triangle.triangulate({'vertices': pts[subset]}, 'e')
    edges = subset[out['edges']]
    segs = edges[rng.choice(len(edges), size=min(m, len(edges)), replace=False)]
elif variant == 'long':
    per_chain = 11
    strips = max(1, m // (per_chain - 1))
    strip = np.minimum(np.floor(pts[:, 1] * strips).astype(np.int64), strips - 1)
    order = np.lexsort((rng.random(n), strip))  # random order inside each strip
    bounds = np.searchsorted(strip[order], np.arange(strips + 1))
    segs = []
    for s in range(strips):
        ids = order[bounds[s]:bounds[s + 1]][:per_chain]
        ids = ids[np.lexsort((pts[ids, 1], pts[ids, 0]))]  # left to right
        segs.extend(zip(ids[:-1], ids[1:]))
    segs = np.array(segs, dtype=np.int64).reshape(-1, 2)
else:
    raise SystemExit(f'unknown PSLG variant {variant!r}')
with open(path, 'w') as f:
    f.write(f'# {variant} PSLG: {n} uniform points, {len(segs)} segments, seed {seed}\n')
    f.write(f'{n} 2 0 0\n')
    f.write(''.join(f'{i} {x!r} {y!r}\n' for i, (x, y) in enumerate(pts.tolist())))
    f.write(f'{len(segs)} 0\n')
    f.write(''.join(f'{i} {a} {b}\n' for i, (a, b) in enumerate(segs.tolist())))
    f.write('0\n')
"""


# Runs in a child Python: reads a mesh's STEM.node and STEM.ele (Triangle's
# formats) and prints its vertex and triangle counts, its smallest angle in
# degrees and how many triangles have an angle below ANGLE.  The smallest angle's
# squared sine is 4 area^2 over the product of the squared lengths of the two
# longer edges (as cgal_bench pslgmesh computes it), a triangle counted when that
# is below sin^2(ANGLE) by more than 1e-9 relative.  Streams the files: plain
# Python, no numpy.
MESH_QUALITY_CHILD = r"""
import json, math, sys
from array import array

stem, angle = sys.argv[1], float(sys.argv[2])

def rows(path):
    with open(path) as f:
        for line in f:
            line = line.split('#', 1)[0].split()
            if line:
                yield line

nodes = rows(stem + '.node')
n = int(next(nodes)[0])
xs, ys = array('d', bytes(8 * n)), array('d', bytes(8 * n))
for i in range(n):
    r = next(nodes)
    if i == 0:
        base = int(r[0])
    xs[i], ys[i] = float(r[1]), float(r[2])
eles = rows(stem + '.ele')
m = int(next(eles)[0])
bound = math.sin(math.radians(angle)) ** 2 * (1.0 - 1e-9)
bad, smallest = 0, 1.0
for _ in range(m):
    r = next(eles)
    a, b, c = int(r[1]) - base, int(r[2]) - base, int(r[3]) - base
    ax, ay, bx, by, cx, cy = xs[a], ys[a], xs[b], ys[b], xs[c], ys[c]
    twice_area = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax)
    e = sorted(((bx - cx) ** 2 + (by - cy) ** 2, (cx - ax) ** 2 + (cy - ay) ** 2,
                (ax - bx) ** 2 + (ay - by) ** 2))
    q = twice_area * twice_area / (e[1] * e[2])
    if q < bound:
        bad += 1
    if q < smallest:
        smallest = q
print(json.dumps({'vertices': n, 'triangles': m, 'bad_triangles': bad,
                  'min_angle': math.degrees(math.asin(math.sqrt(smallest)))}))
"""


class ToolFailure(Exception):
    pass


def log(msg):
    sys.stderr.write(msg + "\n")
    sys.stderr.flush()


GNU_TIME = "/usr/bin/time"


def run_measured(cmd, timeout):
    """Runs cmd in a fresh process; returns (stdout, its peak RSS in MB, its system CPU seconds).

    A child's ru_maxrss starts at the high-water mark of the process it was
    forked from (Linux keeps it across exec), so a measurement taken with
    os.wait4 on a direct child of this script can never read below this
    script's own peak.  GNU time (when installed) is a small C program whose
    child starts from its own tiny footprint: its %M is the command's own
    peak.  Without it, os.wait4's ru_maxrss of the direct child is used (this
    script keeps itself small: inputs are generated in a subprocess).  The
    system seconds (GNU time's %S, else ru_stime) are mostly the kernel zeroing
    fresh pages: on a virtual machine their cost per GB changes from run to run."""
    use_time = os.access(GNU_TIME, os.X_OK)
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err, \
            tempfile.NamedTemporaryFile(suffix=".rss") as rss:
        full = [GNU_TIME, "-f", "%M %S", "-o", rss.name, "--"] + cmd if use_time else cmd
        try:
            # A session of its own so that a timeout kills the whole group.
            proc = subprocess.Popen(full, stdout=out, stderr=err, stdin=subprocess.DEVNULL,
                                    start_new_session=True)
        except OSError as e:
            raise ToolFailure(f"cannot start {full[0]}: {e}")
        timed_out = threading.Event()

        def kill():
            timed_out.set()
            try:
                os.killpg(proc.pid, 9)
            except ProcessLookupError:
                pass

        timer = threading.Timer(timeout, kill)
        timer.start()
        try:
            _, status, usage = os.wait4(proc.pid, 0)
        finally:
            timer.cancel()
        code = os.waitstatus_to_exitcode(status)
        proc.returncode = code  # already reaped: keep Popen from waiting again
        out.seek(0)
        err.seek(0)
        stdout = out.read().decode(errors="replace")
        stderr = err.read().decode(errors="replace")
        peak_kb = usage.ru_maxrss  # Linux: kilobytes
        system_s = usage.ru_stime
        if use_time:
            fields = open(rss.name).read().split()
            if len(fields) >= 2 and fields[-2].isdigit():
                peak_kb = int(fields[-2])
                system_s = float(fields[-1])
    if timed_out.is_set():
        raise ToolFailure(f"timed out after {timeout:g} s")
    if code != 0:
        if use_time and code == 127 and not stdout and "No such file" in stderr:
            raise ToolFailure(f"cannot start {cmd[0]}")
        tail = (stderr.strip() or stdout.strip()).splitlines()[-3:]
        raise ToolFailure(f"exit status {code}" + (": " + " | ".join(tail) if tail else ""))
    return stdout, peak_kb / 1024.0, system_s


def last_json_line(stdout):
    for line in reversed(stdout.strip().splitlines()):
        line = line.strip()
        if line.startswith("{"):
            return json.loads(line)
    raise ToolFailure("no JSON result on stdout")


# ---- the three tools -------------------------------------------------------

def run_clmesh(exe, node, timeout, switches=(), mesh_check=None):
    """clmesh on one input; mesh_check, when given, is called with the output
    files' stem (INPUT.1) before they are deleted and its dict joins the result."""
    if not os.path.isfile(exe):
        raise ToolFailure(f"{exe} not built")
    stem = os.path.splitext(node)[0]
    fd, stats_path = tempfile.mkstemp(suffix=".json", dir=os.path.dirname(node))
    os.close(fd)
    checked = {}
    try:
        _, peak, system_s = run_measured([exe, *switches, "-Q", "--stats-json", stats_path, node],
                                         timeout)
        with open(stats_path) as f:
            stats = json.load(f)
        if mesh_check:
            checked = mesh_check(stem + ".1")
    except (OSError, ValueError) as e:
        raise ToolFailure(f"cannot read the stats JSON: {e}")
    finally:
        os.unlink(stats_path)
        for out in glob.glob(glob.escape(stem) + ".1.*"):  # the mesh written next to the input
            os.unlink(out)
    try:
        seconds = float(stats["seconds"]["compute"])
    except (KeyError, TypeError, ValueError):
        raise ToolFailure("stats JSON has no seconds.compute")
    phases = [(p.get("name", "?"), float(p.get("seconds", 0.0))) for p in stats.get("phases", [])]
    counts = stats.get("counts", {})
    refinement = stats.get("refinement") or {}
    vertices = None
    if counts.get("input_points") is not None and refinement.get("steiner_points") is not None:
        vertices = int(counts["input_points"]) + int(refinement["steiner_points"])
    return {"seconds": seconds, "peak_mb": peak, "system_s": system_s, "phases": phases,
            "triangles": counts.get("triangles"), "device": stats.get("device"),
            "vertices": vertices, "remaining_bad": refinement.get("remaining_bad_triangles"),
            "iterations": refinement.get("iterations"), "refinement": refinement, **checked}


def ensure_triangle_package():
    """True when `import triangle` works in this Python, installing it with pip if needed."""
    probe = [sys.executable, "-c", "import numpy, triangle"]
    if subprocess.run(probe, capture_output=True).returncode == 0:
        return True
    log("bench.py: installing the PyPI package 'triangle' with pip")
    subprocess.run([sys.executable, "-m", "pip", "install", "--quiet", "triangle"],
                   stdout=subprocess.DEVNULL)
    return subprocess.run(probe, capture_output=True).returncode == 0


def run_triangle(triangle, node, timeout, child=TRIANGLE_CHILD, switches=""):
    """Triangle on one input: the native binary when triangle is ("native", PATH),
    else the PyPI package in a child Python (triangle is ("python", available)).
    switches are Triangle's without the dash: "" (Delaunay), "pc" (CDT), "q30"."""
    kind, what = triangle
    if kind == "native":
        return run_native_triangle(what, node, timeout, switches)
    if not what:
        raise ToolFailure("the Python package 'triangle' is not available")
    # The CDT child always runs 'pc'; the others take the switches.
    extra = [switches] if switches and child is TRIANGLE_CHILD else []
    cmd = [sys.executable, "-c", child, node] + extra
    stdout, peak, system_s = run_measured(cmd, timeout)
    r = last_json_line(stdout)
    return {"seconds": float(r["seconds"]), "peak_mb": peak, "system_s": system_s,
            "triangles": r.get("triangles"), "vertices": r.get("vertices"),
            "dt_seconds": r.get("dt_seconds")}


def run_native_triangle(exe, path, timeout, switches, mesh_check=None):
    """The native Triangle binary (-NEP: no output files) on path, timed by its own
    report: seconds = Delaunay + Segment + Hole + Quality milliseconds (file
    reading and writing excluded); dt_seconds = the Delaunay part alone, so that
    for -pc the difference is its segment recovery.  With mesh_check it runs
    with -P instead (writing INPUT.1.node and INPUT.1.ele, outside its timing)
    and mesh_check's dict, from those files, joins the result."""
    if not os.access(exe, os.X_OK):
        raise ToolFailure(f"{exe} not built (bash /work/shared/tools/build-triangle.sh)")
    checked = {}
    if mesh_check:
        stem = os.path.splitext(path)[0]
        try:
            stdout, peak, system_s = run_measured([exe, "-P" + switches, path], timeout)
            checked = mesh_check(stem + ".1")
        finally:
            for out in glob.glob(glob.escape(stem) + ".1.*"):
                os.unlink(out)
    else:
        stdout, peak, system_s = run_measured([exe, "-NEP" + switches, path], timeout)
    ms = {}
    counts = {}
    for line in stdout.splitlines():
        line = line.strip()
        m = re.match(r"(Delaunay|Segment|Hole|Quality) milliseconds:\s*(\d+)", line)
        if m:
            ms[m.group(1)] = int(m.group(2))
        m = re.match(r"Mesh (vertices|triangles):\s*(\d+)", line)
        if m:
            counts[m.group(1)] = int(m.group(2))
    if "Delaunay" not in ms:
        raise ToolFailure("no 'Delaunay milliseconds' in Triangle's report "
                          "(built with -DNO_TIMER?)")
    return {"seconds": sum(ms.values()) / 1000.0, "dt_seconds": ms["Delaunay"] / 1000.0,
            "peak_mb": peak, "system_s": system_s,
            "triangles": counts.get("triangles"), "vertices": counts.get("vertices"), **checked}


def run_cgal(exe, node, timeout, mode="dt", mode_args=()):
    """cgal_bench MODE [MODE_ARGS...] NODE, e.g. mode "mesh" with mode_args ("30",)."""
    if not os.path.isfile(exe):
        raise ToolFailure(f"{exe} not built (needs libcgal-dev at configure time)")
    stdout, peak, system_s = run_measured([exe, mode, *mode_args, node], timeout)
    r = last_json_line(stdout)
    return {"seconds": float(r["seconds"]), "peak_mb": peak, "system_s": system_s,
            "triangles": r.get("triangles"), "vertices": r.get("vertices"),
            "bad_triangles": r.get("bad_triangles"), "min_angle": r.get("min_angle")}


def best_of(k, fn, *args):
    """Best time of k fresh runs; peak memory is the largest seen."""
    best = None
    peak = 0.0
    for _ in range(k):
        r = fn(*args)
        peak = max(peak, r["peak_mb"])
        if best is None or r["seconds"] < best["seconds"]:
            best = r
    best["peak_mb"] = peak
    return best


# ---- inputs ---------------------------------------------------------------

def input_file(bench_dir, dist, n, seed):
    path = os.path.join(bench_dir, f"{dist}-{n}-s{seed}.node")
    if not os.path.isfile(path):
        log(f"bench.py: generating {path}")
        tmp = path + ".tmp"
        # In a subprocess: a million points would raise this script's own
        # peak memory, which its children's ru_maxrss would inherit.
        subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "gen_points.py"),
                        dist, str(n), tmp, "--seed", str(seed)], check=True)
        os.replace(tmp, path)
    return path


def pslg_file(bench_dir, variant, n, seed):
    path = os.path.join(bench_dir, f"pslg-{variant}-{n}-s{seed}.poly")
    if not os.path.isfile(path):
        log(f"bench.py: generating {path}")
        tmp = path + ".tmp"
        proc = subprocess.run([sys.executable, "-c", PSLG_GENERATOR, variant, str(n), tmp,
                               str(seed)], capture_output=True, text=True)
        if proc.returncode != 0:
            raise ToolFailure(f"cannot generate the {variant} PSLG: "
                              + (proc.stderr.strip().splitlines() or ["?"])[-1])
        os.replace(tmp, path)
    return path


def quality_pslg_file(bench_dir, kind, n, seed):
    """The --pslg input KIND (coast, segments) of n vertices, made by gen_pslg.py."""
    path = os.path.join(bench_dir, f"qpslg-{kind}-{n}-s{seed}.poly")
    if not os.path.isfile(path):
        log(f"bench.py: generating {path}")
        tmp = path + ".tmp"
        subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "gen_pslg.py"), kind,
                        str(n), tmp, "--seed", str(seed)], check=True)
        os.replace(tmp, path)
    return path


def mesh_quality(angle, timeout):
    """A mesh_check for run_clmesh / run_native_triangle: MESH_QUALITY_CHILD on
    the output files, for the minimum angle angle (degrees)."""
    def check(stem):
        stdout, _, _ = run_measured([sys.executable, "-c", MESH_QUALITY_CHILD, stem, angle],
                                    timeout)
        return last_json_line(stdout)
    return check


def poly_segment_count(path):
    with open(path) as f:
        lines = (l.split("#", 1)[0].split() for l in f)
        lines = [l for l in lines if l]
    n = int(lines[0][0])
    return int(lines[n + 1][0])


# ---- report ---------------------------------------------------------------

def fmt_s(r):
    return f"{r['seconds']:.3f}" if r else "fail"


def fmt_ratio(a, b):
    if not a or not b or b["seconds"] <= 0:
        return "fail"
    return f"{a['seconds'] / b['seconds']:.2f}"


def fmt_mb(r):
    return f"{r['peak_mb']:.0f}" if r else "fail"


def fmt_system(r):
    return f"{r['system_s']:.2f}" if r else "fail"


def fmt_phases(r):
    if not r:
        return "fail"
    return ", ".join(f"{name}:{sec:.3f}" for name, sec in r["phases"]) or "-"


def fmt_count(r, key):
    if not r:
        return "fail"
    return "-" if r.get(key) is None else str(r[key])


def fmt_bad(r):
    """Triangles below the angle bound, with the smallest angle: '0 (30.00)'."""
    if not r:
        return "fail"
    if r.get("bad_triangles") is None:
        return "-"
    return f"{r['bad_triangles']} ({r['min_angle']:.2f})"


def fmt_vertex_ratio(a, b):
    if not a or not b or not a.get("vertices") or not b.get("vertices"):
        return "fail"
    return f"{a['vertices'] / b['vertices']:.3f}"


def fmt_k(v):
    """A count in a few characters: 950, 12k, 1.2M."""
    if v is None:
        return "?"
    v = int(v)
    if abs(v) < 1000:
        return str(v)
    if abs(v) < 1000000:
        return f"{v / 1000:.1f}k" if abs(v) < 10000 else f"{v / 1000:.0f}k"
    return f"{v / 1e6:.1f}M" if abs(v) < 10000000 else f"{v / 1e6:.0f}M"


# The phases of one refinement iteration, in the thesis's step order.
REFINE_STEPS = ("offcenter_insertion", "missing_point_insertion", "flipflop_deletion")


def fmt_refine_details(r):
    """Per-step seconds, flips and deletions of a clmesh refinement, e.g.
    'steps 1.20/0.30/2.10; flips 600k D + 60k ND; deleted 22k; reinserted 12k'."""
    if not r:
        return "fail"
    phases = dict(r.get("phases") or [])
    ref = r.get("refinement") or {}
    steps = "/".join(f"{phases[p]:.3f}" if p in phases else "-" for p in REFINE_STEPS)
    if "flipping" in phases:  # timed apart from the steps
        steps += f" (+ flipping {phases['flipping']:.3f})"
    text = (f"steps {steps}; flips {fmt_k(ref.get('delaunay_flips'))} D + "
            f"{fmt_k(ref.get('non_delaunay_flips'))} ND; "
            f"deleted {fmt_k(ref.get('deleted_redundant'))}; "
            f"reinserted {fmt_k(ref.get('inserted_more_than_once'))}; "
            f"{ref.get('iterations', '?')} iterations")
    if ref.get("remaining_bad_triangles"):
        text += f"; {ref['remaining_bad_triangles']} bad left"
    return text


def machine_line(device):
    cpu = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    line = f"Host: {cpu}, {os.cpu_count()} logical cores, Python {platform.python_version()}"
    if device:
        line += f"; clmesh device: {device}"
    return line


def run_tools(a, what, tools, failures):
    """Runs each (name, fn, args) or (name, fn, args, warmup_args) of tools, best
    of --repeat, logging as it goes; a tool that fails is recorded in failures
    and gets None.  With warmup_args, fn(*warmup_args) runs first, untimed (e.g.
    clmesh with -C: a failed check fails the tool)."""
    results = {}
    for name, fn, args, *warmup in tools:
        log(f"bench.py: {what}: {name} ...")
        t0 = time.time()
        try:
            if warmup:
                fn(*warmup[0])
            elif fn is run_clmesh and a.repeat == 1:
                fn(*args)  # untimed: PoCL's kernel compilation (see the help)
            results[name] = best_of(a.repeat, fn, *args)
            vertices = results[name].get("vertices")
            log(f"bench.py:   {results[name]['seconds']:.3f} s"
                + (f", {vertices} vertices" if vertices is not None else "")
                + f" (wall {time.time() - t0:.1f} s for {a.repeat} run(s))")
        except ToolFailure as e:
            results[name] = None
            failures.append(f"{what}: {name}: {e}")
            log(f"bench.py:   fail: {e}")
    return results


def compare_triangle_counts(what, results, warnings):
    counts = {k: r["triangles"] for k, r in results.items()
              if r and r.get("triangles") is not None}
    if len(set(counts.values())) > 1:
        warnings.append(f"{what}: triangle counts differ: "
                        + ", ".join(f"{k} {v}" for k, v in counts.items()))


class Setup:
    """What every mode parses and prepares: sizes, tool paths, the input cache."""

    def __init__(self, a, ap):
        self.sizes = [10000] if a.quick else [int(s) for s in a.sizes.replace(" ", "").split(",")
                                              if s]
        if a.repeat < 1:
            ap.error("--repeat must be >= 1")
        self.clmesh = a.clmesh or os.path.join(a.build_dir, "clmesh")
        self.cgal = a.cgal or os.path.join(a.build_dir, "cgal_bench")
        self.bench_dir = os.path.join(a.build_dir, "bench")
        os.makedirs(self.bench_dir, exist_ok=True)
        self.triangle = choose_triangle(a.triangle, a.build_dir)


def choose_triangle(option, build_dir):
    """("native", PATH) or ("python", available): --triangle PATH, --triangle python,
    or by default BUILD/triangle-native when it is built, else the PyPI package."""
    if option and option != "python":
        return ("native", option)
    native = os.path.join(build_dir, "triangle-native")
    if option is None and os.access(native, os.X_OK):
        return ("native", native)
    return ("python", ensure_triangle_package())


def triangle_note(triangle, outputs="-NEP (no output files)"):
    """How Triangle ran and was timed, for the notes under a table."""
    kind, what = triangle
    if kind == "native":
        return (f"Triangle: the native binary {os.path.relpath(what, ROOT)} (triangle.c 1.6, "
                f"-O3 -march=native, built by build-triangle.sh), run with {outputs} and timed by its own report (Delaunay + Segment + Hole + Quality "
                "milliseconds), file reading and writing excluded.")
    return ("Triangle: the PyPI package 'triangle' in a child Python, timing only the "
            "triangle.triangulate call; its peak memory includes Python, numpy and the "
            "loaded points.")


def distributions(a, ap):
    dists = [d for d in a.dists.replace(" ", "").split(",") if d]
    for d in dists:
        if d not in DISTS:
            ap.error(f"unknown distribution {d!r} (choose from {', '.join(DISTS)})")
    return dists


def main(argv=None):
    ap = argparse.ArgumentParser(description="clmesh vs Triangle vs CGAL on the thesis distributions")
    ap.add_argument("--sizes", default=None,
                    help="comma-separated point counts (default 100000,1000000; "
                         "100000 with --quality)")
    ap.add_argument("--dists", default=",".join(DISTS),
                    help=f"comma-separated subset of {','.join(DISTS)}")
    ap.add_argument("--quick", action="store_true", help="10000 points only")
    ap.add_argument("--repeat", type=int, default=1, help="best of K runs (default 1)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--markdown", metavar="FILE",
                    help="also write the table, with the command, date, machine and clmesh "
                         "commit, as this mode's section of FILE (other sections kept)")
    ap.add_argument("--triangle", metavar="PATH",
                    help="native Triangle binary (default BUILD/triangle-native when built, "
                         "else the PyPI package); 'python' forces the PyPI package")
    ap.add_argument("--build-dir", default=os.path.join(ROOT, "build"))
    ap.add_argument("--clmesh", help="clmesh binary (default BUILD/clmesh)")
    ap.add_argument("--cgal", help="cgal_bench binary (default BUILD/cgal_bench)")
    ap.add_argument("--timeout", type=float, default=600, help="seconds per run (default 600)")
    ap.add_argument("--cdt", action="store_true",
                    help="constrained Delaunay of generated PSLGs (N points, N/10 segments)")
    ap.add_argument("--variants", default="short,long",
                    help="with --cdt: comma-separated subset of short,long")
    ap.add_argument("--quality", action="store_true",
                    help="quality meshes of the distributions: clmesh --refine qmv and qm "
                         "-qANGLE vs Triangle 'qANGLE' vs CGAL refine_Delaunay_mesh_2 (time, "
                         "output vertices, clmesh's per-step times and flips)")
    ap.add_argument("--angles", default=None,
                    help="with --quality (default 20,30) or --pslg (default 30): "
                         "comma-separated minimum angles in degrees")
    ap.add_argument("--pslg", action="store_true",
                    help="quality meshes of large generated PSLGs: clmesh -pqANGLE / -pcqANGLE "
                         "vs Triangle (same switches) vs CGAL refine_Delaunay_mesh_2 (time, "
                         "vertices, triangles below the angle, peak memory)")
    ap.add_argument("--kinds", default="coast,segments,square",
                    help="with --pslg: comma-separated subset of coast,segments,square")
    ap.add_argument("--algorithms", default="qmv,qm",
                    help="with --quality: comma-separated clmesh refinement variants to run, "
                         "subset of qmv,qm (default both)")
    a = ap.parse_args(argv)
    if a.cdt + a.quality + a.pslg > 1:
        ap.error("--cdt, --quality and --pslg cannot be combined")
    if a.angles is None:
        a.angles = "30" if a.pslg else "20,30"
    a.sizes_given = a.sizes is not None or a.quick
    if a.sizes is None:
        a.sizes = "100000" if a.quality or a.pslg else "100000,1000000"
    if a.cdt:
        return main_cdt(a, ap)
    if a.quality:
        return main_quality(a, ap)
    if a.pslg:
        return main_pslg(a, ap)

    dists = distributions(a, ap)
    setup = Setup(a, ap)
    sizes, clmesh, cgal, bench_dir = setup.sizes, setup.clmesh, setup.cgal, setup.bench_dir
    triangle = setup.triangle

    rows, failures, warnings = [], [], []
    device = None
    for dist in dists:
        for n in sizes:
            node = input_file(bench_dir, dist, n, a.seed)
            results = run_tools(a, f"{dist} n={n}", (
                ("clmesh", run_clmesh, (clmesh, node, a.timeout)),
                ("Triangle", run_triangle, (triangle, node, a.timeout)),
                ("CGAL", run_cgal, (cgal, node, a.timeout))), failures)
            cl, tr, cg = results["clmesh"], results["Triangle"], results["CGAL"]
            if cl and cl.get("device"):
                device = cl["device"]
            compare_triangle_counts(f"{dist} n={n}", results, warnings)
            rows.append([dist, str(n), fmt_s(cl), fmt_s(tr), fmt_s(cg), fmt_ratio(cl, tr),
                         fmt_ratio(cl, cg), fmt_mb(cl), fmt_mb(tr), fmt_phases(cl)])

    header = ["dist", "n", "clmesh compute s", "Triangle s", "CGAL s", "clmesh/Triangle",
              "clmesh/CGAL", "clmesh peak MB", "Triangle peak MB", "clmesh phases (s)"]
    return report(a, header, rows,
                  [f"Best of {a.repeat} run(s), seed {a.seed}; times exclude file reading and writing; "
                   "ratios are clmesh time / other time (below 1: clmesh is faster); "
                   "peak MB is each process's maximum resident set size.",
                   triangle_note(setup.triangle)],
                  device, warnings, failures, "dt", "Delaunay triangulation")


def main_cdt(a, ap):
    variants = [v for v in a.variants.replace(" ", "").split(",") if v]
    for v in variants:
        if v not in ("short", "long"):
            ap.error(f"unknown PSLG variant {v!r} (choose from short, long)")
    setup = Setup(a, ap)
    sizes, clmesh, cgal, bench_dir = setup.sizes, setup.clmesh, setup.cgal, setup.bench_dir
    triangle = setup.triangle

    rows, failures, warnings = [], [], []
    device = None
    for variant in variants:
        for n in sizes:
            try:
                poly = pslg_file(bench_dir, variant, n, a.seed)
                m = poly_segment_count(poly)
            except ToolFailure as e:
                failures.append(f"{variant} n={n}: {e}")
                log(f"bench.py:   fail: {e}")
                continue
            results = run_tools(a, f"cdt {variant} n={n} m={m}", (
                ("clmesh", run_clmesh, (clmesh, poly, a.timeout, ("-pc",))),
                ("Triangle", run_triangle, (triangle, poly, a.timeout, TRIANGLE_CDT_CHILD,
                                              "pc")),
                ("CGAL", run_cgal, (cgal, poly, a.timeout, "cdt"))), failures)
            cl, tr, cg = results["clmesh"], results["Triangle"], results["CGAL"]
            if cl and cl.get("device"):
                device = cl["device"]
            compare_triangle_counts(f"cdt {variant} n={n}", results, warnings)
            # Segment insertion on its own: clmesh's phase, Triangle's -pc time
            # less its Delaunay triangulation of the same points.
            ours = dict(cl["phases"]).get("constraint_insertion") if cl else None
            theirs = (tr["seconds"] - tr["dt_seconds"]
                      if tr and tr.get("dt_seconds") is not None else None)
            rows.append([variant, str(n), str(m), fmt_s(cl), fmt_s(tr), fmt_s(cg),
                         fmt_ratio(cl, tr), fmt_ratio(cl, cg),
                         "fail" if ours is None else f"{ours:.3f}",
                         "fail" if theirs is None else f"{theirs:.3f}",
                         fmt_ratio({"seconds": ours} if ours is not None else None,
                                   {"seconds": theirs} if theirs is not None else None),
                         fmt_mb(cl), fmt_mb(tr), fmt_mb(cg), fmt_phases(cl)])

    header = ["segments", "n", "m", "clmesh compute s", "Triangle -pc s", "CGAL CDT s",
              "clmesh/Triangle", "clmesh/CGAL", "clmesh constraint insertion s",
              "Triangle segment recovery s", "insertion/recovery", "clmesh peak MB",
              "Triangle peak MB", "CGAL peak MB", "clmesh phases (s)"]
    return report(a, header, rows,
                  [f"Constrained Delaunay triangulation of the whole convex hull (-pc); best of "
                   f"{a.repeat} run(s), seed {a.seed}; n uniform points, m segments ('short': random "
                   "edges of the Delaunay triangulation of a quarter of the points; 'long': x-monotone "
                   "chains in horizontal strips, segments about 1/11 of the square long); times "
                   "exclude file reading and writing; ratios are clmesh time / other time (below 1: "
                   "clmesh is faster); Triangle's segment recovery is its -pc time less its "
                   "Delaunay triangulation of the same points.",
                   triangle_note(setup.triangle)],
                  device, warnings, failures, "cdt", "Constrained Delaunay triangulation")


# clmesh's refinement variants in --quality: (--algorithms name, --refine value, label).
QUALITY_ALGORITHMS = (("qmv", "qmv", "QM-V"), ("qm", "qm", "QM"))


def main_quality(a, ap):
    dists = distributions(a, ap)
    angles = parse_angles(a, ap)
    wanted = [s for s in a.algorithms.replace(" ", "").lower().split(",") if s]
    known = [name for name, _, _ in QUALITY_ALGORITHMS]
    for w in wanted:
        if w not in known:
            ap.error(f"unknown refinement algorithm {w!r} (choose from {', '.join(known)})")
    if not wanted:
        ap.error("--algorithms needs at least one of qmv,qm")
    algorithms = [alg for alg in QUALITY_ALGORITHMS if alg[0] in wanted]  # table order
    setup = Setup(a, ap)
    sizes, clmesh, cgal, bench_dir = setup.sizes, setup.clmesh, setup.cgal, setup.bench_dir
    triangle = setup.triangle

    labels = [label for _, _, label in algorithms]
    rows, failures, warnings = [], [], []
    device = None
    for dist in dists:
        for n in sizes:
            node = input_file(bench_dir, dist, n, a.seed)
            for angle in angles:
                tools = [(label, run_clmesh, (clmesh, node, a.timeout,
                                              ("--refine", refine, f"-q{angle}")))
                         for _, refine, label in algorithms]
                tools += [("Triangle", run_triangle, (triangle, node, a.timeout,
                                                      TRIANGLE_CHILD, f"q{angle}")),
                          ("CGAL", run_cgal, (cgal, node, a.timeout, "mesh", (angle,)))]
                results = run_tools(a, f"quality {dist} n={n} q{angle}", tools, failures)
                tr = results["Triangle"]
                for label in labels:
                    cl = results[label]
                    if cl and cl.get("device"):
                        device = cl["device"]
                    if cl and cl.get("remaining_bad"):
                        warnings.append(f"quality {dist} n={n} q{angle}: {label} left "
                                        f"{cl['remaining_bad']} bad triangle(s)")
                rows.append([dist, str(n), angle]
                            + [fmt_s(results[k]) for k in labels + ["Triangle", "CGAL"]]
                            + [fmt_ratio(results[k], tr) for k in labels]
                            + [fmt_count(results[k], "vertices")
                               for k in labels + ["Triangle", "CGAL"]]
                            + [fmt_vertex_ratio(results[k], tr) for k in labels]
                            + [fmt_mb(results[k]) for k in labels + ["Triangle"]]
                            + [fmt_system(results[k]) for k in labels + ["Triangle"]]
                            + [fmt_refine_details(results[labels[0]])])

    header = (["dist", "n", "angle"] + [f"{k} s" for k in labels] + ["Triangle s", "CGAL s"]
              + [f"{k}/Triangle" for k in labels]
              + [f"vertices {k}" for k in labels] + ["vertices Triangle", "vertices CGAL"]
              + [f"vertex ratio {k}/Triangle" for k in labels]
              + [f"peak MB {k}" for k in labels + ["Triangle"]]
              + [f"system s {k}" for k in labels + ["Triangle"]]
              + [f"{labels[0]} steps 1/2/3 s, flips"])
    return report(a, header, rows,
                  [f"Quality meshes of the convex hull with minimum angle ANGLE degrees "
                   f"(clmesh --refine qmv|qm -qANGLE, Triangle -qANGLE, CGAL "
                   f"refine_Delaunay_mesh_2 with Delaunay_mesh_criteria_2(sin^2 ANGLE)); best of "
                   f"{a.repeat} run(s), seed {a.seed}; times exclude file reading and writing "
                   "(clmesh: seconds.compute); X/Triangle is the time ratio (below 1: clmesh is "
                   "faster); clmesh vertices = input points + Steiner points, Triangle vertices = "
                   "its output vertices, CGAL vertices = number_of_vertices(); the vertex "
                   "ratio is clmesh's vertices / Triangle's. Peak MB: the process's maximum "
                   "resident set (the largest of the runs); system s: its system CPU seconds in "
                   "the run whose time is shown, file reading included (mostly the kernel "
                   "zeroing fresh pages, whose cost per GB drifts on a shared virtual machine).",
                   f"Last column ({labels[0]}): seconds of step 1 (off-center insertion) / step 2 "
                   "(missing point insertion) / step 3 (flip-flop deletion) over all iterations, "
                   "plus the 'flipping' phase timed apart from them (these phases include the "
                   "initial Delaunay triangulation's missing point insertion and flipping); "
                   "step 3's Delaunay (D) and non-Delaunay (ND) flips; redundant Steiner points "
                   "deleted; points inserted again after a deletion; refinement iterations.",
                   triangle_note(setup.triangle)],
                  device, warnings, failures, "quality", "Quality meshes")


# --pslg inputs: (kind, Triangle switches without q, default size, the convex hull is meshed,
# the triangles' area is bounded by 1/n).
PSLG_KINDS = (("coast", "p", 100000, False, False), ("segments", "pc", 1000000, True, False),
              ("square", "p", 1000000, False, True))


def area_switch(n):
    """-a's 1/n as Triangle reads a number: digits and a point, no exponent."""
    return "a" + f"{1.0 / n:.12f}".rstrip("0")


def main_pslg(a, ap):
    kinds = [k for k in a.kinds.replace(" ", "").split(",") if k]
    known = [k for k, _, _, _, _ in PSLG_KINDS]
    for k in kinds:
        if k not in known:
            ap.error(f"unknown --pslg input {k!r} (choose from {', '.join(known)})")
    angles = parse_angles(a, ap)
    setup = Setup(a, ap)
    clmesh, cgal, bench_dir, triangle = setup.clmesh, setup.cgal, setup.bench_dir, setup.triangle

    rows, failures, warnings = [], [], []
    device = None
    for kind, switches, default_n, hull, area_bound in PSLG_KINDS:
        if kind not in kinds:
            continue
        for n in setup.sizes if a.sizes_given else [default_n]:
            try:
                poly = quality_pslg_file(bench_dir, kind, n, a.seed)
                m = poly_segment_count(poly)
            except (ToolFailure, subprocess.CalledProcessError) as e:
                failures.append(f"{kind} n={n}: cannot generate the input: {e}")
                continue
            for angle in angles:
                check = mesh_quality(angle, a.timeout)
                tail = f"q{angle}" + (area_switch(n) if area_bound else "")
                sw = f"-{switches}{tail}"
                tools = [("clmesh", run_clmesh, (clmesh, poly, a.timeout, (sw,), check),
                          (clmesh, poly, a.timeout, (sw, "-C"))),
                         ("Triangle", run_pslg_triangle, (triangle, poly, a.timeout,
                                                          switches + tail, check))]
                # cgal_bench's pslgmesh bounds angles only.
                if not area_bound:
                    tools.append(("CGAL", run_cgal, (cgal, poly, a.timeout, "pslgmesh",
                                                     (angle,) + (("hull",) if hull else ()))))
                results = run_tools(a, f"pslg {kind} n={n} m={m} {sw}", tools, failures)
                cl, tr, cg = results["clmesh"], results["Triangle"], results.get("CGAL")
                if cl and cl.get("device"):
                    device = cl["device"]
                if cl and (cl.get("refinement") or {}).get("stop_reason", "done") != "done":
                    warnings.append(f"pslg {kind} n={n} {sw}: clmesh's refinement stopped: "
                                    f"{cl['refinement']['stop_reason']}")
                def cell(k, fmt):  # "-": a tool not run on this input
                    return fmt(results[k]) if k in results else "-"
                tools3 = ("clmesh", "Triangle", "CGAL")
                rows.append([kind, str(n), str(m), sw]
                            + [cell(k, fmt_s) for k in tools3]
                            + [fmt_ratio(cl, tr), cell("CGAL", lambda c: fmt_ratio(cl, c))]
                            + [cell(k, lambda r: fmt_count(r, "vertices")) for k in tools3]
                            + [fmt_vertex_ratio(cl, tr)]
                            + [cell(k, fmt_bad) for k in tools3]
                            + [cell(k, fmt_mb) for k in tools3])

    header = (["input", "n", "m", "switches", "clmesh s", "Triangle s", "CGAL s",
               "clmesh/Triangle", "clmesh/CGAL", "vertices clmesh", "vertices Triangle",
               "vertices CGAL", "vertex ratio clmesh/Triangle",
               "below angle clmesh (min)", "below angle Triangle (min)",
               "below angle CGAL (min)", "peak MB clmesh", "peak MB Triangle", "peak MB CGAL"])
    return report(a, header, rows,
                  [f"Quality meshes of PSLGs made by scripts/gen_pslg.py (seed {a.seed}; n "
                   "vertices, m segments): 'coast' is a fractal closed outline (half the "
                   "vertices) around small closed islands of 50 vertices, every island a hole "
                   "(one hole seed each), meshed with -pqANGLE; 'segments' is n points on a "
                   "jittered grid, n/10 cells holding a short segment instead of a point "
                   "(non-crossing, well apart), meshed with -pcqANGLE (the convex hull); "
                   "'square' is the unit square meshed with -pqANGLEa(1/n), a lattice-like "
                   "mesh whose in-circle tests are mostly exact cocircular ties (no CGAL run: "
                   "cgal_bench bounds angles only).",
                   "clmesh: build/clmesh SWITCHES -Q --stats-json, time = seconds.compute; an "
                   "untimed run with -C (exact check of the output mesh) comes first, a failed "
                   "check fails the row.  Triangle: the same switches.  CGAL: build/cgal_bench "
                   "pslgmesh ANGLE [hull] INPUT.poly (refine_Delaunay_mesh_2 on a "
                   "Constrained_Delaunay_triangulation_2<Epick> with the segments, the holes "
                   "as seeds and Delaunay_mesh_criteria_2(b = sin^2 ANGLE), i.e. CGAL's "
                   "radius-edge bound B = 1 / (2 sin ANGLE); with 'hull' the convex hull edges "
                   "are constraints too; CGAL guarantees termination only up to about 20.7 "
                   "degrees), timing insertion and refinement.",
                   f"Best of {a.repeat} run(s); times exclude file reading and writing; "
                   "ratios are clmesh time / other time (below 1: clmesh is faster).  Vertices: "
                   "clmesh's and Triangle's output .node files, CGAL's vertices of faces in the "
                   "domain; the vertex ratio is clmesh's / Triangle's.  Below angle: triangles "
                   "of the output with an angle below ANGLE (computed from the output files for "
                   "clmesh and Triangle, in cgal_bench for CGAL, the same way: squared sine of "
                   "the smallest angle below sin^2 ANGLE by more than 1e-9 relative), with the "
                   "mesh's smallest angle in degrees; triangles at input angles below ANGLE "
                   "cannot be improved by any of the tools.  Peak MB: each process's maximum "
                   "resident set.",
                   triangle_note(setup.triangle, "-P (writing the .node and .ele files read "
                                 "back for the counts)")],
                  device, warnings, failures, "pslg", "Quality meshes of PSLGs")


def run_pslg_triangle(triangle, poly, timeout, switches, mesh_check):
    kind, what = triangle
    if kind != "native":
        raise ToolFailure("--pslg needs the native Triangle binary "
                          "(bash /work/shared/tools/build-triangle.sh, or --triangle PATH)")
    return run_native_triangle(what, poly, timeout, switches, mesh_check)


def parse_angles(a, ap):
    angles = [s for s in a.angles.replace(" ", "").split(",") if s]
    for angle in angles:
        try:
            if not 0 < float(angle) < 60:
                raise ValueError
        except ValueError:
            ap.error(f"bad angle {angle!r} (degrees, between 0 and 60)")
    return angles


def report(a, header, rows, description, device, warnings, failures, mode, title):
    """Prints a markdown table with its notes; with --markdown FILE also writes
    them, with the command line, date, machine and clmesh commit, as the section
    of this mode in FILE (see write_markdown)."""
    lines = ["| " + " | ".join(header) + " |",
             "|" + "|".join("---" for _ in header) + "|"]
    lines += ["| " + " | ".join(r) + " |" for r in rows]
    notes = [machine_line(device)] + description
    notes += [f"Warning: {w}" for w in warnings]
    notes += [f"Failed: {f}" for f in failures]
    print("\n".join(lines + [""] + notes) + "\n", end="")
    if a.markdown:
        write_markdown(a.markdown, mode, title, lines, notes, device)
    return 0


# ---- the --markdown file --------------------------------------------------

MARKDOWN_MODES = ("dt", "cdt", "quality", "pslg", "refine", "batch")  # section order in the file
MARKDOWN_HEAD = """# Benchmarks

This file is written by `scripts/bench.py --markdown docs/benchmarks.md` (and
`scripts/bench_refine.py --markdown docs/benchmarks.md` for `-r`,
`scripts/bench_batch.py --markdown docs/benchmarks.md` for batches): each run
replaces the section of its mode (Delaunay, `--cdt`, `--quality`, `--pslg`,
refining, batches) and keeps the others. Do not edit it by hand.

clmesh, Shewchuk's Triangle and CGAL run side by side on the same inputs, each
in a fresh process, timing the meshing alone (no file reading or writing). The
ratios are clmesh's time over the other tool's: below 1, clmesh is faster.
Absolute times drift on a shared machine such as this project's 2-core virtual
machines (other jobs, the price of fresh memory; each section gives the load
average); the ratios of a table come from one run, each tool measured right
after the others on the same input.
"""


START_LOAD = os.getloadavg()  # other jobs on the machine when the run began


def load_average(load):
    return ", ".join(f"{x:.1f}" for x in load)


# What the measured binaries are built from: edits elsewhere (documentation)
# do not make a commit dirty.
CODE_PATHS = ("cl", "host", "include", "cli", "cmake", "CMakeLists.txt", "scripts")


def git_commit():
    """The clmesh commit measured, with '-dirty' when its code (CODE_PATHS) differs from it."""
    try:
        head = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"],
                              capture_output=True, text=True, check=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", ROOT, "status", "--porcelain",
                                "--untracked-files=no", "--", *CODE_PATHS],
                               capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"
    return head + ("-dirty" if dirty else "")


def command_line():
    """This run's command line, as typed from the repository root."""
    args = [os.path.relpath(os.path.abspath(sys.argv[0]), ROOT)] + sys.argv[1:]
    return " ".join(["python3"] + [arg if re.fullmatch(r"[\w./,=:+-]+", arg) else repr(arg)
                                   for arg in args])


def write_markdown(path, mode, title, table, notes, device):
    """Writes this mode's section of the markdown file at path: the title, the
    command, date, machine and commit, the table and its notes. The sections of
    the other modes already in the file are kept, in MARKDOWN_MODES order."""
    sections = {}
    try:
        with open(path) as f:
            old = f.read()
        for m in re.finditer(r"<!-- bench\.py: (\w+) -->\n(.*?)<!-- bench\.py: end -->\n",
                             old, re.S):
            sections[m.group(1)] = m.group(2)
    except OSError:
        pass
    cpu = machine_line(None).split(",")[0].removeprefix("Host: ")
    body = [f"## {title}", "",
            "```sh", command_line(), "```", "",
            f"- Date: {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}",
            f"- Machine: {cpu}, {os.cpu_count()} logical cores, {platform.system()} "
            f"{platform.release()}",
            f"- clmesh commit: {git_commit()}",
            f"- Load average (1, 5, 15 min) at the start: {load_average(START_LOAD)}; "
            f"at the end: {load_average(os.getloadavg())}, on {os.cpu_count()} logical cores "
            "(Triangle and CGAL run on one core, clmesh's kernels on all)",
            f"- clmesh device: {device or 'unknown'}", ""]
    body += table + [""]
    body += [f"- {n}" for n in notes[1:]]  # notes[0] is the machine line, given above
    sections[mode] = "\n".join(body) + "\n"
    out = [MARKDOWN_HEAD]
    for m in MARKDOWN_MODES:
        if m in sections:
            out.append(f"<!-- bench.py: {m} -->\n{sections[m]}<!-- bench.py: end -->\n")
    directory = os.path.dirname(os.path.abspath(path))
    os.makedirs(directory, exist_ok=True)
    with open(path + ".tmp", "w") as f:
        f.write("\n".join(out))
    os.replace(path + ".tmp", path)


if __name__ == "__main__":
    sys.exit(main())
