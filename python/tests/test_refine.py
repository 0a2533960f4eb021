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
