#!/usr/bin/env python3
"""Benchmark clmesh against Triangle and CGAL on the thesis point distributions.

For each distribution and size the input is generated once (cached in
build/bench/) and then three tools triangulate it, each in a fresh process:

  clmesh    build/clmesh -Q --stats-json F.json INPUT.node
            time = seconds.compute from the stats JSON (plus the per-phase times)
  Triangle  the PyPI package `triangle` (installed with pip if missing) in a
            child Python that loads the points first and times only
            triangle.triangulate({'vertices': pts}, '')
  CGAL      build/cgal_bench dt INPUT.node  (Delaunay_triangulation_2, Epick,
            range insert; times only the construction)

Peak memory is each tool process's maximum resident set size, from GNU time's
%M when /usr/bin/time exists, otherwise from os.wait4's ru_maxrss.  Triangle's figure includes the Python interpreter, numpy and the
loaded point array.  --repeat K keeps the best time of K runs (and the largest
peak memory).  A tool that fails gets 'fail' in its cells; the reasons are
listed under the table.

Usage: python3 scripts/bench.py [--quick] [--sizes 100000,1000000]
           [--dists uniform,grid] [--repeat K] [--markdown OUT.md]
"""
import argparse
import glob
import json
import os
import platform
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
t0 = time.perf_counter()
out = triangle.triangulate({'vertices': pts}, '')
t1 = time.perf_counter()
print(json.dumps({'seconds': t1 - t0, 'triangles': int(len(out['triangles'])),
                  'vertices': int(len(out['vertices']))}))
"""


class ToolFailure(Exception):
    pass


def log(msg):
    sys.stderr.write(msg + "\n")
    sys.stderr.flush()


GNU_TIME = "/usr/bin/time"


def run_measured(cmd, timeout):
    """Runs cmd in a fresh process; returns (stdout, its peak RSS in MB).

    A child's ru_maxrss starts at the high-water mark of the process it was
    forked from (Linux keeps it across exec), so a measurement taken with
    os.wait4 on a direct child of this script can never read below this
    script's own peak.  GNU time (when installed) is a small C program whose
    child starts from its own tiny footprint: its %M is the command's own
    peak.  Without it, os.wait4's ru_maxrss of the direct child is used (this
    script keeps itself small: inputs are generated in a subprocess)."""
    use_time = os.access(GNU_TIME, os.X_OK)
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err, \
            tempfile.NamedTemporaryFile(suffix=".rss") as rss:
        full = [GNU_TIME, "-f", "%M", "-o", rss.name, "--"] + cmd if use_time else cmd
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
        if use_time:
            lines = open(rss.name).read().split()
            if lines and lines[-1].isdigit():
                peak_kb = int(lines[-1])
    if timed_out.is_set():
        raise ToolFailure(f"timed out after {timeout:g} s")
    if code != 0:
        if use_time and code == 127 and not stdout and "No such file" in stderr:
            raise ToolFailure(f"cannot start {cmd[0]}")
        tail = (stderr.strip() or stdout.strip()).splitlines()[-3:]
        raise ToolFailure(f"exit status {code}" + (": " + " | ".join(tail) if tail else ""))
    return stdout, peak_kb / 1024.0


def last_json_line(stdout):
    for line in reversed(stdout.strip().splitlines()):
        line = line.strip()
        if line.startswith("{"):
            return json.loads(line)
    raise ToolFailure("no JSON result on stdout")


# ---- the three tools -------------------------------------------------------

def run_clmesh(exe, node, timeout):
    if not os.path.isfile(exe):
        raise ToolFailure(f"{exe} not built")
    stem = node[:-len(".node")]
    fd, stats_path = tempfile.mkstemp(suffix=".json", dir=os.path.dirname(node))
    os.close(fd)
    try:
        _, peak = run_measured([exe, "-Q", "--stats-json", stats_path, node], timeout)
        with open(stats_path) as f:
            stats = json.load(f)
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
    return {"seconds": seconds, "peak_mb": peak, "phases": phases,
            "triangles": counts.get("triangles"), "device": stats.get("device")}


def ensure_triangle_package():
    """True when `import triangle` works in this Python, installing it with pip if needed."""
    probe = [sys.executable, "-c", "import numpy, triangle"]
    if subprocess.run(probe, capture_output=True).returncode == 0:
        return True
    log("bench.py: installing the PyPI package 'triangle' with pip")
    subprocess.run([sys.executable, "-m", "pip", "install", "--quiet", "triangle"],
                   stdout=subprocess.DEVNULL)
    return subprocess.run(probe, capture_output=True).returncode == 0


def run_triangle(available, node, timeout):
    if not available:
        raise ToolFailure("the Python package 'triangle' is not available")
    stdout, peak = run_measured([sys.executable, "-c", TRIANGLE_CHILD, node], timeout)
    r = last_json_line(stdout)
    return {"seconds": float(r["seconds"]), "peak_mb": peak, "triangles": r.get("triangles")}


def run_cgal(exe, node, timeout):
    if not os.path.isfile(exe):
        raise ToolFailure(f"{exe} not built (needs libcgal-dev at configure time)")
    stdout, peak = run_measured([exe, "dt", node], timeout)
    r = last_json_line(stdout)
    return {"seconds": float(r["seconds"]), "peak_mb": peak, "triangles": r.get("triangles")}


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


# ---- report ---------------------------------------------------------------

def fmt_s(r):
    return f"{r['seconds']:.3f}" if r else "fail"


def fmt_ratio(a, b):
    if not a or not b or b["seconds"] <= 0:
        return "fail"
    return f"{a['seconds'] / b['seconds']:.2f}"


def fmt_mb(r):
    return f"{r['peak_mb']:.0f}" if r else "fail"


def fmt_phases(r):
    if not r:
        return "fail"
    return ", ".join(f"{name}:{sec:.3f}" for name, sec in r["phases"]) or "-"


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


def main(argv=None):
    ap = argparse.ArgumentParser(description="clmesh vs Triangle vs CGAL on the thesis distributions")
    ap.add_argument("--sizes", default="100000,1000000",
                    help="comma-separated point counts (default 100000,1000000)")
    ap.add_argument("--dists", default=",".join(DISTS),
                    help=f"comma-separated subset of {','.join(DISTS)}")
    ap.add_argument("--quick", action="store_true", help="10000 points only")
    ap.add_argument("--repeat", type=int, default=1, help="best of K runs (default 1)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--markdown", metavar="OUT", help="also write the table to OUT")
    ap.add_argument("--build-dir", default=os.path.join(ROOT, "build"))
    ap.add_argument("--clmesh", help="clmesh binary (default BUILD/clmesh)")
    ap.add_argument("--cgal", help="cgal_bench binary (default BUILD/cgal_bench)")
    ap.add_argument("--timeout", type=float, default=600, help="seconds per run (default 600)")
    a = ap.parse_args(argv)

    sizes = [10000] if a.quick else [int(s) for s in a.sizes.replace(" ", "").split(",") if s]
    dists = [d for d in a.dists.replace(" ", "").split(",") if d]
    for d in dists:
        if d not in DISTS:
            ap.error(f"unknown distribution {d!r} (choose from {', '.join(DISTS)})")
    if a.repeat < 1:
        ap.error("--repeat must be >= 1")
    clmesh = a.clmesh or os.path.join(a.build_dir, "clmesh")
    cgal = a.cgal or os.path.join(a.build_dir, "cgal_bench")
    bench_dir = os.path.join(a.build_dir, "bench")
    os.makedirs(bench_dir, exist_ok=True)
    have_triangle = ensure_triangle_package()

    rows, failures, warnings = [], [], []
    device = None
    for dist in dists:
        for n in sizes:
            node = input_file(bench_dir, dist, n, a.seed)
            results = {}
            for name, fn, args in (("clmesh", run_clmesh, (clmesh, node, a.timeout)),
                                   ("Triangle", run_triangle, (have_triangle, node, a.timeout)),
                                   ("CGAL", run_cgal, (cgal, node, a.timeout))):
                log(f"bench.py: {dist} n={n}: {name} ...")
                t0 = time.time()
                try:
                    results[name] = best_of(a.repeat, fn, *args)
                    log(f"bench.py:   {results[name]['seconds']:.3f} s "
                        f"(wall {time.time() - t0:.1f} s for {a.repeat} run(s))")
                except ToolFailure as e:
                    results[name] = None
                    failures.append(f"{dist} n={n}: {name}: {e}")
                    log(f"bench.py:   fail: {e}")
            cl, tr, cg = results["clmesh"], results["Triangle"], results["CGAL"]
            if cl and cl.get("device"):
                device = cl["device"]
            counts = {k: r["triangles"] for k, r in results.items() if r and r.get("triangles") is not None}
            if len(set(counts.values())) > 1:
                warnings.append(f"{dist} n={n}: triangle counts differ: "
                                + ", ".join(f"{k} {v}" for k, v in counts.items()))
            rows.append([dist, str(n), fmt_s(cl), fmt_s(tr), fmt_s(cg), fmt_ratio(cl, tr),
                         fmt_ratio(cl, cg), fmt_mb(cl), fmt_mb(tr), fmt_phases(cl)])

    header = ["dist", "n", "clmesh compute s", "Triangle s", "CGAL s", "clmesh/Triangle",
              "clmesh/CGAL", "clmesh peak MB", "Triangle peak MB", "clmesh phases (s)"]
    lines = ["| " + " | ".join(header) + " |",
             "|" + "|".join("---" for _ in header) + "|"]
    lines += ["| " + " | ".join(r) + " |" for r in rows]
    notes = ["", machine_line(device),
             f"Best of {a.repeat} run(s), seed {a.seed}; times exclude file reading and writing; "
             "ratios are clmesh time / other time (below 1: clmesh is faster); "
             "peak MB is each process's maximum resident set size (Triangle's includes Python and numpy)."]
    notes += [f"Warning: {w}" for w in warnings]
    notes += [f"Failed: {f}" for f in failures]
    text = "\n".join(lines + notes) + "\n"
    print(text, end="")
    if a.markdown:
        with open(a.markdown, "w") as f:
            f.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
