"""-r through the dict interface, as in the triangle package: 'triangles',
'triangle_attributes' and 'triangle_max_area' in; bad meshes raise
InputError, missing keys too."""

import numpy as np
import pytest

import clmesh
from conftest import triangle_set

# A unit square with a point inside, cut into four counter-clockwise triangles.
SQUARE = np.array([[0, 0], [1, 0], [1, 1], [0, 1], [0.5, 0.25]])
FAN = np.array([[0, 1, 4], [1, 2, 4], [2, 0, 4], [0, 2, 3]])


def mesh(**extra):
    return dict(vertices=SQUARE, triangles=FAN, **extra)


@pytest.mark.parametrize("tri, switches, message", [
    ({"vertices": SQUARE}, "r", "'triangles' is missing"),
    (mesh(), "ra", "'triangle_max_area' is missing"),
    (mesh(triangle_max_area=[0.1, 0.1, 0.1]), "ra", "triangle_max_area: 3 rows, expected 4"),
    (mesh(triangle_max_area=[0.1, np.nan, 0.1, 0.1]), "ra",
     "triangle 1: its maximum area is not a number"),
    (mesh(triangle_attributes=np.zeros((3, 2))), "r", "triangle_attributes: 3 rows, expected 4"),
    (mesh(triangle_attributes=[[1], [2], [np.inf], [4]]), "r", "triangle_attributes: row 2"),
    ({"vertices": SQUARE, "triangles": [[0, 1, 5]]}, "r", "triangles: row 0"),
    ({"vertices": SQUARE, "triangles": [[0, 1]]}, "r", "triangles: expected shape"),
    ({"vertices": SQUARE, "triangles": [[0, 4, 1]]}, "r", "triangle 0: its corners are in "
                                                          "clockwise order"),
    ({"vertices": SQUARE, "triangles": [[0, 1, 4], [0, 1, 2]]}, "r",
     "triangle 1: it overlaps triangle 0"),
    ({"vertices": SQUARE, "triangles": [[0, 1, 1]]}, "r", "a corner is repeated"),
])
def test_bad_meshes_raise_input_error(tri, switches, message):
    with pytest.raises(clmesh.InputError, match=message):
        clmesh.triangulate(tri, switches)


def test_without_r_the_triangles_are_ignored():
    # As Triangle: a previous output's triangles (even bad ones) change nothing.
    points = {"vertices": SQUARE}
    plain = clmesh.triangulate(points)
    given = clmesh.triangulate({"vertices": SQUARE, "triangles": [[0, 4, 1]],
                                "triangle_max_area": [-1]})
    assert np.array_equal(plain["triangles"], given["triangles"])
    assert "triangle_attributes" not in given


def test_max_areas_are_ignored_without_a_alone():
    # -r without -a (or with -a<number>) reads no maximum areas: a bad list is no error.
    for switches in ("r", "ra0.5"):
        clmesh.triangulate(mesh(triangle_max_area=[np.nan] * 4), switches)


def test_a_delaunay_output_refined_without_bounds_is_itself():
    # -r alone only restores the constrained Delaunay property: a Delaunay
    # mesh (in general position) comes back with the same triangles.
    points = np.random.default_rng(5).random((200, 2))
    first = clmesh.triangulate({"vertices": points}, "")
    again = clmesh.triangulate(first, "r")
    assert np.array_equal(again["vertices"], first["vertices"])
    assert triangle_set(again["triangles"]) == triangle_set(first["triangles"])


def _areas(vertices, triangles):
    a, b, c = (vertices[triangles[:, k]] for k in range(3))
    return 0.5 * ((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1])
                  - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0]))


def _area_bound_at(vertices, triangles, max_area, points):
    """For each point, the .area bound of the input triangle holding it (edges
    included): the largest of them where it lies on an edge between two (the
    refined triangle takes the bound of the one it descends from), inf for
    none (-1); NaN where no input triangle holds it."""
    corners = vertices[triangles]  # (T, 3, 2)
    bound = np.full(len(points), np.nan)
    for t, (a, b, c) in enumerate(corners):
        inside = np.ones(len(points), bool)
        for p, q in ((a, b), (b, c), (c, a)):
            inside &= ((q[0] - p[0]) * (points[:, 1] - p[1])
                       - (q[1] - p[1]) * (points[:, 0] - p[0])) >= 0
        value = max_area[t] if max_area[t] > 0 else np.inf
        bound[inside] = np.fmax(bound[inside], value)
    return bound


def _ring_mesh():
    """A square with a square hole, meshed by clmesh -pq: the mesh to refine."""
    outer = np.array([[0, 0], [4, 0], [4, 4], [0, 4]], float)
    inner = np.array([[1.5, 1.5], [2.5, 1.5], [2.5, 2.5], [1.5, 2.5]])
    loop = np.array([[0, 1], [1, 2], [2, 3], [3, 0]])
    pslg = dict(vertices=np.r_[outer, inner], segments=np.r_[loop, loop + 4], holes=[[2, 2]])
    return pslg, clmesh.triangulate(pslg, "pq")


def test_refined_mesh_keeps_domain_attributes_and_bounds():
    pslg, given = _ring_mesh()
    t = len(given["triangles"])
    numbers = np.arange(t, dtype=float)
    given["triangle_attributes"] = np.c_[numbers, -2 * numbers]
    given["triangle_max_area"] = np.where(numbers % 2 == 0, 0.05, -1.0)
    result = clmesh.run(given, "rpq30a")
    assert result.check() == []
    out = result.mesh
    # The input's vertices first, the same domain, segments and holes kept.
    assert np.array_equal(out["vertices"][:len(given["vertices"])], given["vertices"])
    assert np.isclose(_areas(out["vertices"], out["triangles"]).sum(), 15.0, rtol=1e-12)
    assert "segments" in out and np.array_equal(out["holes"], [[2, 2]])
    # Every attribute row is one input triangle's.
    attributes = out["triangle_attributes"]
    assert attributes.shape == (len(out["triangles"]), 2)
    parent = attributes[:, 0].astype(int)
    assert np.array_equal(attributes[:, 1], -2 * parent)
    # The bound of the input triangle holding a triangle's centroid holds (on
    # an edge between two, the one the triangle descends from: the larger, at
    # least).
    centroids = out["vertices"][out["triangles"]].mean(axis=1)
    bound = _area_bound_at(given["vertices"], given["triangles"], given["triangle_max_area"],
                           centroids)
    assert not np.isnan(bound).any()
    areas = _areas(out["vertices"], out["triangles"])
    assert (areas <= bound * (1 + 1e-9)).all()
    assert np.isfinite(bound).sum() > np.isinf(bound).sum()  # the bounded half got the points


def test_refined_twice_as_with_the_command_line():
    pslg, given = _ring_mesh()
    once = clmesh.triangulate(dict(given, holes=pslg["holes"]), "rpq30a0.05")
    twice = clmesh.run(dict(once, holes=pslg["holes"]), "rpq30a0.02")
    assert twice.check() == []
    assert len(twice.mesh["vertices"]) > len(once["vertices"])
    assert _areas(twice.mesh["vertices"], twice.mesh["triangles"]).max() <= 0.02 * (1 + 1e-9)


def test_vertex_counts_near_the_triangle_package():
    triangle = pytest.importorskip("triangle")
    _, given = _ring_mesh()
    for switches in ("rq30a0.01", "rpq30a0.005"):
        ours = len(clmesh.triangulate(given, switches)["vertices"])
        theirs = len(triangle.triangulate(given, switches)["vertices"])
        assert 0.8 < ours / theirs <= 1.05, (switches, ours, theirs)
