"""-o2 (six-node triangles) against the triangle package: the same shapes,
and the same triangles with the same middle nodes (coordinates, markers,
attributes); every middle node the midpoint of its triangle's edge."""

import numpy as np
import pytest

import clmesh
from conftest import DATASETS, load, random_points, triangle


def six_node_triangles(mesh):
    """Each triangle as the set of its corners, each with the middle node of
    the opposite edge (coordinates, marker, attributes): numbering (and which
    copy of a duplicate vertex stands for it) ignored."""
    vertices, markers = mesh["vertices"], mesh.get("vertex_markers")
    attributes = mesh.get("vertex_attributes")

    def node(k):
        return (tuple(vertices[k]), None if markers is None else int(markers[k, 0]),
                None if attributes is None else tuple(attributes[k]))

    return sorted(tuple(sorted((node(row[i]), node(row[3 + i])) for i in range(3)))
                  for row in mesh["triangles"].tolist())


def check_midpoints(mesh):
    """Columns 3-5 are the middles of the edges opposite columns 0-2, numbered
    after the corners, one node per edge shared by the triangles on its sides."""
    vertices, triangles = mesh["vertices"], mesh["triangles"]
    corners, middles = triangles[:, :3], triangles[:, 3:]
    assert middles.min() > corners.max()
    assert middles.max() == len(vertices) - 1
    for i in range(3):
        ends = vertices[corners[:, [(i + 1) % 3, (i + 2) % 3]]]
        assert np.array_equal(vertices[middles[:, i]], ends.sum(axis=1) / 2)
    edge_of = {}
    for row in triangles.tolist():
        for i in range(3):
            edge = tuple(sorted((row[(i + 1) % 3], row[(i + 2) % 3])))
            assert edge_of.setdefault(edge, row[3 + i]) == row[3 + i]
    assert sorted(edge_of.values()) == list(range(corners.max() + 1, len(vertices)))


# A duplicate vertex, which -j leaves out.
DUPLICATE = {"vertices": [[0, 0], [1, 0], [0, 1], [1, 0], [1, 1], [0.3, 0.6]]}


@pytest.mark.parametrize("name, switches", [
    ("dots", "o2"), ("la", "po2"), ("la", "pAo2n"), ("face", "pco2"), ("A", "po2B"),
    ("la", "po2j"), ("duplicate", "o2"), ("duplicate", "jo2")])
def test_second_order_matches_triangle(name, switches):
    data = dict(DUPLICATE) if name == "duplicate" else load(DATASETS, name)
    if name == "la":
        data["vertex_attributes"] = np.arange(len(data["vertices"]), dtype=float)
    ours, theirs = clmesh.triangulate(data, switches), triangle.triangulate(data, switches)
    assert {k: (v.dtype, v.shape) for k, v in ours.items()} == \
        {k: (v.dtype, v.shape) for k, v in theirs.items()}
    assert ours["triangles"].shape[1] == 6
    check_midpoints(ours)
    assert six_node_triangles(ours) == six_node_triangles(theirs)


def test_second_order_markers_are_those_of_the_edges():
    data = load(DATASETS, "la")
    mesh = clmesh.triangulate(data, "peo2")
    middle = {tuple(sorted((row[(i + 1) % 3], row[(i + 2) % 3]))): row[3 + i]
              for row in mesh["triangles"].tolist() for i in range(3)}
    for edge, marker in zip(mesh["edges"].tolist(), mesh["edge_markers"].ravel().tolist()):
        assert mesh["vertex_markers"][middle[tuple(sorted(edge))], 0] == marker


def test_second_order_of_a_quality_mesh():
    points = random_points(300, 41)
    plain, six = clmesh.triangulate({"vertices": points}, "q"), \
        clmesh.triangulate({"vertices": points}, "qo2")
    assert np.array_equal(six["triangles"][:, :3], plain["triangles"])
    assert np.array_equal(six["vertices"][:len(plain["vertices"])], plain["vertices"])
    check_midpoints(six)
