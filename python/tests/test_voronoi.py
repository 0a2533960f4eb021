"""clmesh.voronoi() against triangle.voronoi() on the same points: the same
Voronoi points, finite edges and rays. Both number the Voronoi points as
their Delaunay triangles, which they number differently: the points are
matched through the triangles (unique for these inputs, which have no four
cocircular points), and edges and rays compared through that matching."""

from fractions import Fraction

import numpy as np
import pytest

import clmesh
from conftest import DATASETS, load, random_points, triangle, triangle_set

EPS = 2.0**-53


def exact_circumcentre(corners):
    """The circumcentre of three points, in rationals."""
    (ax, ay), (bx, by), (cx, cy) = [(Fraction(x), Fraction(y)) for x, y in corners.tolist()]
    bx, by, cx, cy = bx - ax, by - ay, cx - ax, cy - ay
    twice_area = 2 * (bx * cy - by * cx)
    b2, c2 = bx * bx + by * by, cx * cx + cy * cy
    return (ax + (cy * b2 - by * c2) / twice_area, ay + (bx * c2 - cx * b2) / twice_area)


def compare_voronoi(points):
    points = np.asarray(points, dtype=float)
    points_a, edges_a, origin_a, direct_a = clmesh.voronoi(points)
    points_b, edges_b, origin_b, direct_b = triangle.voronoi(points)
    for ours, theirs in [(points_a, points_b), (edges_a, edges_b), (origin_a, origin_b),
                         (direct_a, direct_b)]:
        assert ours.dtype == theirs.dtype and ours.shape == theirs.shape
    # matched[t]: Triangle's number of our Voronoi point (triangle) t.
    triangles = np.sort(clmesh.delaunay(points), axis=1)
    theirs = {tuple(t): k for k, t in enumerate(np.sort(triangle.delaunay(points), 1).tolist())}
    assert len(theirs) == len(triangles) == len(triangle_set(triangles))
    matched = np.array([theirs[tuple(t)] for t in triangles.tolist()], dtype=int)

    # The same points, to 1e-12 relative; except where Triangle's own
    # circumcentre is off (far centres of nearly flat hull triangles, which
    # Triangle computes in plain floating point): there ours must be within
    # the library's bound of the exact centre.
    offset = np.abs(points_a - points[triangles[:, 0]])
    scale = np.abs(points).max()
    close = np.abs(points_a - points_b[matched]) <= 1e-12 * (np.abs(points_b[matched]) + scale)
    for t in np.nonzero(~close.all(axis=1))[0]:
        exact = np.array([float(c) for c in exact_circumcentre(points[triangles[t]])])
        bound = 4 * EPS * offset[t] + EPS * np.abs(points_a[t]) + 1e-300
        assert (np.abs(points_a[t] - exact) <= bound).all(), (t, points_a[t], exact)
    assert close.all(axis=1).mean() > 0.99

    def edge_set(edges):
        return sorted(tuple(sorted(edge)) for edge in edges.tolist())

    assert edge_set(matched[edges_a]) == edge_set(edges_b)
    # Rays: the same origins and directions (the hull edge turned a quarter
    # clockwise, as long as the edge: the same difference of input points).
    rays_a = sorted(zip(matched[origin_a].tolist(), map(tuple, direct_a.tolist())))
    rays_b = sorted(zip(origin_b.tolist(), map(tuple, direct_b.tolist())))
    assert rays_a == rays_b


@pytest.mark.parametrize("name", ["spiral", "dots", "diamond_02_00009", "greenland"])
def test_voronoi_matches_triangle_on_bundled_points(name):
    compare_voronoi(load(DATASETS, name)["vertices"])


@pytest.mark.parametrize("n, seed", [(3, 31), (2000, 32)])
def test_voronoi_matches_triangle_on_random_points(n, seed):
    compare_voronoi(random_points(n, seed))


def test_voronoi_is_the_dual_of_the_delaunay_triangulation():
    points = random_points(500, 33)
    centres, edges, origins, directions = clmesh.voronoi(points)
    mesh = clmesh.triangulate({"vertices": points}, "n")  # numbered as the Voronoi points
    triangles, neighbors = mesh["triangles"], mesh["neighbors"]
    assert len(centres) == len(triangles)
    # Each point is its triangle's circumcentre.
    distances = np.linalg.norm(points[triangles] - centres[:, None, :], axis=2)
    assert np.allclose(distances, distances[:, :1], rtol=1e-9, atol=0)
    # A finite edge between every two neighbours ...
    inner = {tuple(sorted((t, u))) for t, row in enumerate(neighbors.tolist()) for u in row
             if u >= 0}
    assert sorted(map(tuple, np.sort(edges, axis=1).tolist())) == sorted(inner)
    # ... and a ray across every hull edge a -> b (counter-clockwise), along
    # its outward normal (b - a turned a quarter clockwise).
    t, i = np.nonzero(neighbors < 0)
    along = points[triangles[t, (i + 2) % 3]] - points[triangles[t, (i + 1) % 3]]
    normals = np.stack([along[:, 1], -along[:, 0]], axis=1)
    expected = sorted(zip(t.tolist(), map(tuple, normals.tolist())))
    assert sorted(zip(origins.tolist(), map(tuple, directions.tolist()))) == expected


def test_triangulate_ignores_v_as_the_triangle_package_does():
    data = load(DATASETS, "la")
    assert clmesh.triangulate(data, "pv").keys() == clmesh.triangulate(data, "p").keys()


def test_voronoi_of_collinear_points_is_empty():
    # No triangle, so no Voronoi point (triangle.voronoi raises KeyError here).
    points, edges, origins, directions = clmesh.voronoi([[0, 0], [1, 0], [2, 0]])
    assert [(a.dtype.name, a.shape) for a in (points, edges, origins, directions)] == [
        ("float64", (0, 2)), ("int32", (0, 2)), ("int32", (0,)), ("float64", (0, 2))]


@pytest.mark.parametrize("points", [[[0, 0], [1, 0]], [[0, 0], [1, 0], [np.nan, 1]]])
def test_voronoi_checks_its_input(points):
    with pytest.raises(clmesh.InputError):
        clmesh.voronoi(points)
