#!/usr/bin/env python3
"""Per-call cost of clmesh.triangulate against triangle.triangulate: many
calls on small point sets, where the fixed cost of a call (argument checks,
device launches, copies) dominates. Not a test; needs clmesh, numpy and
triangle installed (bash scripts/test-python.sh puts them in build/venv).

    build/venv/bin/python scripts/bench_python.py --calls 1000 --points 1000
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


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--calls", type=int, default=1000)
    parser.add_argument("--points", type=int, default=1000)
    parser.add_argument("--switches", default="", help="Triangle's switches, e.g. q30")
    args = parser.parse_args()

    import clmesh
    import triangle

    rng = np.random.default_rng(1)
    inputs = [{"vertices": rng.random((args.points, 2))} for _ in range(args.calls)]
    ours = seconds_per_call(clmesh.triangulate, inputs, args.switches)
    theirs = seconds_per_call(triangle.triangulate, inputs, args.switches)
    # The library's own share: upload to download, as --stats-json reports it.
    stats = [clmesh.run(tri, args.switches).statistics() for tri in inputs[:100]]
    compute = sum(s["seconds"]["compute"] for s in stats) / len(stats)
    print(f"{args.calls} calls, {args.points} points, switches {args.switches!r}, "
          f"device {stats[0]['device']}")
    print(f"clmesh.triangulate   {ours * 1e3:8.3f} ms per call "
          f"(device compute {compute * 1e3:.3f} ms)")
    print(f"triangle.triangulate {theirs * 1e3:8.3f} ms per call")
    print(f"ratio clmesh/triangle {ours / theirs:7.2f}")


if __name__ == "__main__":
    main()
