#!/usr/bin/env python3
"""clmesh.triangulate against triangle.triangulate on the same points: many
calls on small point sets, where the fixed cost of a call (argument checks,
device launches, copies) dominates, then one call on a large set. Not a
test; needs clmesh, numpy and triangle installed (bash scripts/test-python.sh
puts them in build/venv).

    build/venv/bin/python scripts/bench_python.py --calls 1000 --points 1000 --large 1000000
    build/venv/bin/python scripts/bench_python.py --many 2000 --points 2000 --pslg 500

--many N times batches instead: clmesh.triangulate_many on N point sets of
--points uniform random points (with --switches), then on N coastline PSLGs
of --pslg vertices (scripts/gen_pslg.py's coast, seeds 1 to N; -pq30),
against a Python loop of clmesh.triangulate and a loop of
triangle.triangulate on the same inputs (each after one warm-up call).

Per small call, clmesh's time is split into its parts: the Python layer
(clmesh/_input.py checking and converting the dict, clmesh/_output.py
building the output dict), the compiled call (clmesh._clmesh.triangulate:
copies in and out of the library, the library's host work and the device
work), and within that the device compute as --stats-json reports it
(seconds.compute: upload to download).
"""

import argparse
import time

import numpy as np


def seconds_per_call(triangulate, inputs, switches):
    triangulate(inputs[0], switches)  # warm up: device, built kernels
    start = time.perf_counter()
    for tri in inputs:
        triangulate(tri, switches)
    return (time.perf_counter() - start) / len(inputs)


def clmesh_parts(inputs, switches):
    """Seconds per call of each part of clmesh.triangulate (what it runs, in
    turn): input checks, the compiled call, the output dict; and the device
    compute within the compiled call."""
    import clmesh
    from clmesh import _clmesh
    from clmesh._input import arrays
    from clmesh._output import mesh_dict

    clmesh.triangulate(inputs[0], switches)  # warm up: device, built kernels
    parts = dict(python_input=0.0, compiled=0.0, python_output=0.0, compute=0.0)
    for tri in inputs:
        t0 = time.perf_counter()
        given = arrays(tri)
        t1 = time.perf_counter()
        run = _clmesh.triangulate(_clmesh.input(**given, switches=switches),
                                  switches=switches, device="")
        t2 = time.perf_counter()
        mesh_dict(run, tri)
        t3 = time.perf_counter()
        parts["python_input"] += t1 - t0
        parts["compiled"] += t2 - t1
        parts["python_output"] += t3 - t2
        parts["compute"] += clmesh.Result(run, None).statistics()["seconds"]["compute"]
    return {key: value / len(inputs) for key, value in parts.items()}


def one_call(triangulate, tri, switches):
    start = time.perf_counter()
    mesh = triangulate(tri, switches)
    return time.perf_counter() - start, len(mesh["triangles"])


def coast_pslgs(count, vertices):
    """`count` coastline PSLGs of about `vertices` vertices (gen_pslg.py's
    coast with seeds 1 to count) as the triangle package's dicts."""
    import pathlib
    import random
    import sys

    sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
    from gen_pslg import coast

    pslgs = []
    for seed in range(1, count + 1):
        points, segments, holes = coast(vertices, random.Random(seed))
        pslg = {"vertices": np.array(points), "segments": np.array(segments, dtype=np.int32)}
        if holes:
            pslg["holes"] = np.array(holes)
        pslgs.append(pslg)
    return pslgs


def many(inputs, switches, what):
    """clmesh.triangulate_many against loops of clmesh.triangulate and
    triangle.triangulate on `inputs`."""
    import clmesh
    import triangle

    def timed(mesh_all):
        start = time.perf_counter()
        meshes = mesh_all()
        return time.perf_counter() - start, sum(len(m["triangles"]) for m in meshes)

    for warm_up in (clmesh.triangulate, triangle.triangulate):
        warm_up(inputs[0], switches)
    batch, triangles = timed(lambda: clmesh.triangulate_many(inputs, switches))
    loop, loop_triangles = timed(lambda: [clmesh.triangulate(tri, switches) for tri in inputs])
    theirs, their_triangles = timed(lambda: [triangle.triangulate(tri, switches)
                                             for tri in inputs])
    assert triangles == loop_triangles, "the batch and the loop differ"
    n = len(inputs)
    print(f"{n} {what}, switches {switches!r}: {triangles} triangles "
          f"(Triangle {their_triangles})")
    for name, seconds in (("clmesh.triangulate_many", batch), ("loop of clmesh.triangulate", loop),
                          ("loop of triangle.triangulate", theirs)):
        print(f"{name:29}{seconds:8.3f} s ({seconds / n * 1e3:.3f} ms per input)")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--calls", type=int, default=1000)
    parser.add_argument("--points", type=int, default=1000)
    parser.add_argument("--large", type=int, default=1000000,
                        help="points of the single large call (0: none)")
    parser.add_argument("--switches", default="", help="Triangle's switches, e.g. q30")
    parser.add_argument("--many", type=int, default=0,
                        help="time batches of this many inputs instead (triangulate_many)")
    parser.add_argument("--pslg", type=int, default=500,
                        help="with --many: vertices of each coastline PSLG (0: none)")
    args = parser.parse_args()

    import clmesh
    import triangle

    rng = np.random.default_rng(1)
    if args.many:
        print(f"device {clmesh.run({'vertices': rng.random((3, 2))}).statistics()['device']}")
        many([{"vertices": rng.random((args.points, 2))} for _ in range(args.many)],
             args.switches, f"point sets of {args.points} points")
        if args.pslg:
            many(coast_pslgs(args.many, args.pslg), "pq30",
                 f"coastline PSLGs of {args.pslg} vertices")
        return
    inputs = [{"vertices": rng.random((args.points, 2))} for _ in range(args.calls)]
    parts = clmesh_parts(inputs, args.switches)
    ours = parts["python_input"] + parts["compiled"] + parts["python_output"]
    theirs = seconds_per_call(triangle.triangulate, inputs, args.switches)
    device = clmesh.run(inputs[0], args.switches).statistics()["device"]
    print(f"{args.calls} calls, {args.points} points, switches {args.switches!r}, "
          f"device {device}")
    print(f"clmesh.triangulate   {ours * 1e3:8.3f} ms per call")
    print(f"  Python layer       {(parts['python_input'] + parts['python_output']) * 1e3:8.3f} ms "
          f"(input {parts['python_input'] * 1e3:.3f}, output {parts['python_output'] * 1e3:.3f})")
    print(f"  compiled call      {parts['compiled'] * 1e3:8.3f} ms "
          f"(device compute {parts['compute'] * 1e3:.3f})")
    print(f"triangle.triangulate {theirs * 1e3:8.3f} ms per call")
    print(f"ratio clmesh/triangle {ours / theirs:7.2f}")

    if args.large:
        # The first call on a new size may include PoCL compiling kernel
        # variants for it: each tool runs twice, the second call is reported.
        tri = {"vertices": np.random.default_rng(2).random((args.large, 2))}
        first, _ = one_call(clmesh.triangulate, tri, args.switches)
        ours, triangles = one_call(clmesh.triangulate, tri, args.switches)
        one_call(triangle.triangulate, tri, args.switches)
        theirs, their_triangles = one_call(triangle.triangulate, tri, args.switches)
        compute = clmesh.run(tri, args.switches).statistics()["seconds"]["compute"]
        print(f"1 call, {args.large} points ({triangles} triangles; Triangle {their_triangles})")
        print(f"clmesh.triangulate   {ours:8.3f} s (first call {first:.3f} s, "
              f"device compute {compute:.3f} s)")
        print(f"triangle.triangulate {theirs:8.3f} s")
        print(f"ratio clmesh/triangle {ours / theirs:7.2f}")


if __name__ == "__main__":
    main()
