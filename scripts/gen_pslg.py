#!/usr/bin/env python3
"""Generate large planar straight-line graphs (.poly) for the quality-meshing benchmark.

Usage: gen_pslg.py KIND N OUT.poly [--seed S]

KIND is one of
  coast     a coastline: N vertices in all, about half on one closed outer
            outline and half on small closed islands inside it, every island a
            hole (the mesh is the water between the coast and the islands; one
            hole seed per island, at its centre).  The outline is star-shaped
            around the origin, r(t) = 1 + noise(t) with the noise made by
            periodic midpoint displacement (Hurst exponent 0.7: a
            fractal-looking rim; control points every 8 vertices, linear in
            between), scaled into [0.7, 1.3] so r > 0 and the polygon is
            simple.  The islands sit on a jittered grid of cells of side h
            inside the disk of radius 0.6;
            each is star-shaped around its centre (50 vertices, radius 0.3 h
            times 1 +- 0.3 noise, centre jittered by +- 0.1 h), so it stays
            within 0.49 h of its cell centre: islands neither touch each other
            nor the outline.
  segments  N points and N/10 segments in the unit square: the square is cut
            into N - N/10 cells (rows of a near-square grid, filled row by
            row); a random N/10 of the cells hold a segment (two endpoints,
            half-length 0.2 cell, random direction, centred within 0.05 cell
            of the cell centre), the others one point jittered by +- 0.3 cell.
            No two segments cross, and no point comes closer than 0.2 cell to
            a segment of another cell.  Meant for -pc (the convex hull is the
            domain): there is no enclosing boundary.
  square    the unit square: 4 vertices and its 4 sides (N is not used: the
            benchmark bounds the triangles' area by 1/N instead).

Deterministic for a given (KIND, N, seed) on any Python 3: only the standard
library's Mersenne Twister is used.  Vertices are numbered from 1 and written
with repr(), which round-trips the doubles exactly.
"""
import argparse
import math
import random
import sys

KINDS = ("coast", "segments", "square")
ISLAND_VERTICES = 50


def star_polygon(rnd, cx, cy, radius, spread, n, harmonics, decay):
    """n vertices of a closed polygon star-shaped around (cx, cy): radius * (1 + noise),
    noise a random sum of `harmonics` sines with amplitudes k^-decay, scaled into
    [-spread, spread]."""
    waves = [(k, k ** -decay, rnd.random() * 2.0 * math.pi) for k in range(1, harmonics + 1)]
    angles = [2.0 * math.pi * i / n for i in range(n)]
    noise = [sum(a * math.sin(k * t + p) for k, a, p in waves) for t in angles]
    return star_from_noise(cx, cy, radius, spread, angles, noise)


def fractal_polygon(rnd, radius, spread, n, hurst):
    """n vertices of a closed polygon star-shaped around the origin whose radius
    noise comes from periodic midpoint displacement (amplitude 2^(-level * hurst)) on
    a power of two of control angles, at most n/8 of them, interpolated linearly in
    between (so the finest wiggles span about 8 vertices)."""
    controls = 4
    while controls * 2 <= max(4, n // 8):
        controls *= 2
    noise = [rnd.gauss(0.0, 1.0) for _ in range(4)]
    amplitude = 1.0
    while len(noise) < controls:
        amplitude *= 2.0 ** -hurst
        refined = []
        for i, v in enumerate(noise):
            mid = 0.5 * (v + noise[(i + 1) % len(noise)]) + amplitude * rnd.gauss(0.0, 1.0)
            refined += [v, mid]
        noise = refined
    angles = [2.0 * math.pi * i / n for i in range(n)]
    sampled = []
    for i in range(n):
        u = i * controls / n
        j = int(u)
        f = u - j
        sampled.append((1.0 - f) * noise[j] + f * noise[(j + 1) % controls])
    return star_from_noise(0.0, 0.0, radius, spread, angles, sampled)


def star_from_noise(cx, cy, radius, spread, angles, noise):
    """The points radius * (1 + noise scaled into [-spread, spread]) at the angles."""
    mean = sum(noise) / len(noise)
    peak = max(abs(v - mean) for v in noise) or 1.0
    scale = spread / peak
    return [(cx + radius * (1.0 + scale * (v - mean)) * math.cos(t),
             cy + radius * (1.0 + scale * (v - mean)) * math.sin(t))
            for t, v in zip(angles, noise)]


def coast(n, rnd):
    """(points, segments (0-based), holes) of the coastline PSLG."""
    outline_n = max(16, n // 2)
    islands_wanted = max(0, (n - outline_n) // ISLAND_VERTICES)
    outline = fractal_polygon(rnd, 1.0, 0.3, outline_n, 0.7)
    points = list(outline)
    segments = [(i, (i + 1) % outline_n) for i in range(outline_n)]
    holes = []
    if islands_wanted:
        h = math.sqrt(math.pi * 0.55 ** 2 / islands_wanted)
        cells = []
        while len(cells) < islands_wanted:  # shrink the cells until enough fit
            h *= 0.97
            k = int(math.ceil(0.6 / h))
            cells = [((i + 0.5) * h, (j + 0.5) * h) for j in range(-k, k) for i in range(-k, k)
                     if math.hypot((i + 0.5) * h, (j + 0.5) * h) <= 0.6 - h]
        rnd.shuffle(cells)
        for x, y in sorted(cells[:islands_wanted]):
            cx = x + 0.1 * h * (2.0 * rnd.random() - 1.0)
            cy = y + 0.1 * h * (2.0 * rnd.random() - 1.0)
            base = len(points)
            points += star_polygon(rnd, cx, cy, 0.3 * h, 0.3, ISLAND_VERTICES, 3, 1.0)
            segments += [(base + i, base + (i + 1) % ISLAND_VERTICES)
                         for i in range(ISLAND_VERTICES)]
            holes.append((cx, cy))
    return points, segments, holes


def segment_field(n, rnd):
    """(points, segments (0-based), no holes) of the jittered-grid PSLG."""
    m = n // 10
    cells = n - m
    cols = max(1, int(math.ceil(math.sqrt(cells))))
    rows = (cells + cols - 1) // cols
    h = 1.0 / max(cols, rows)
    with_segment = set(rnd.sample(range(cells), m))
    points, segments = [], []
    r = rnd.random
    for c in range(cells):
        x0, y0 = (c % cols + 0.5) * h, (c // cols + 0.5) * h
        if c in with_segment:
            cx, cy = x0 + 0.05 * h * (2 * r() - 1), y0 + 0.05 * h * (2 * r() - 1)
            t = r() * math.pi
            dx, dy = 0.2 * h * math.cos(t), 0.2 * h * math.sin(t)
            segments.append((len(points), len(points) + 1))
            points += [(cx - dx, cy - dy), (cx + dx, cy + dy)]
        else:
            points.append((x0 + 0.3 * h * (2 * r() - 1), y0 + 0.3 * h * (2 * r() - 1)))
    return points, segments, []


def write_poly(path, points, segments, holes, comment):
    chunk = 1 << 16
    with open(path, "w") as f:
        f.write(f"# {comment}\n{len(points)} 2 0 0\n")
        for s in range(0, len(points), chunk):
            f.write("".join(f"{i + 1} {x!r} {y!r}\n"
                            for i, (x, y) in enumerate(points[s:s + chunk], start=s)))
        f.write(f"{len(segments)} 0\n")
        for s in range(0, len(segments), chunk):
            f.write("".join(f"{i + 1} {a + 1} {b + 1}\n"
                            for i, (a, b) in enumerate(segments[s:s + chunk], start=s)))
        f.write(f"{len(holes)}\n")
        f.write("".join(f"{i + 1} {x!r} {y!r}\n" for i, (x, y) in enumerate(holes)))


def unit_square(n, rnd):
    """The unit square's corners and sides, no hole (n and rnd are not used)."""
    return [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)], [(0, 1), (1, 2), (2, 3), (3, 0)], []


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("kind", choices=KINDS)
    ap.add_argument("n", type=int)
    ap.add_argument("out")
    ap.add_argument("--seed", type=int, default=1)
    a = ap.parse_args(argv)
    if a.n < 20:
        ap.error("N must be >= 20")
    rnd = random.Random(a.seed)
    make = {"coast": coast, "segments": segment_field, "square": unit_square}[a.kind]
    points, segments, holes = make(a.n, rnd)
    write_poly(a.out, points, segments, holes,
               f"generated by scripts/gen_pslg.py {a.kind} {a.n} --seed {a.seed}: "
               f"{len(points)} vertices, {len(segments)} segments, {len(holes)} holes")
    return 0


if __name__ == "__main__":
    sys.exit(main())
