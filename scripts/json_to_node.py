#!/usr/bin/env python3
"""Convert a JSON array of [x, y] points (delaunator's fixtures) to a Triangle .node file.

Usage: json_to_node.py IN.json [OUT.node]     (OUT defaults to IN with .node)

Coordinates are written with repr(), which round-trips every double exactly,
so near-degenerate fixtures keep their exact bits.  Vertices are numbered from
0, like the indices of the JSON array.
"""
import json
import os
import sys


def fmt(v):
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        raise ValueError(f"not a number: {v!r}")
    return str(v) if isinstance(v, int) else repr(float(v))


def convert(src, dst):
    with open(src) as f:
        pts = json.load(f)
    if not isinstance(pts, list):
        raise ValueError(f"{src}: expected a JSON array of [x, y] pairs")
    lines = [f"{len(pts)} 2 0 0"]
    for i, p in enumerate(pts):
        if not isinstance(p, list) or len(p) != 2:
            raise ValueError(f"{src}: point {i} is not an [x, y] pair: {p!r}")
        lines.append(f"{i} {fmt(p[0])} {fmt(p[1])}")
    lines.append(f"# converted from {os.path.basename(src)} by scripts/json_to_node.py")
    with open(dst, "w") as f:
        f.write("\n".join(lines) + "\n")
    return len(pts)


def main(argv):
    if len(argv) not in (2, 3) or argv[1] in ("-h", "--help"):
        sys.stderr.write(__doc__)
        return 2
    src = argv[1]
    dst = argv[2] if len(argv) == 3 else os.path.splitext(src)[0] + ".node"
    n = convert(src, dst)
    print(f"{dst}: {n} points")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
