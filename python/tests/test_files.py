"""clmesh.load and clmesh.loads: Triangle's files as input dicts, the same as
the triangle package's (but for its reading of regions), errors naming the
file and line."""

import numpy as np
import pytest

import clmesh
from conftest import DATASETS, triangle

NAMES = ["A", "la", "face", "box", "spiral", "dots", "square_circle_hole", "double_hex",
         "double_hex3", "greenland", "ell", "bbox.1"]


@pytest.mark.parametrize("name", NAMES)
def test_load_gives_the_triangle_package_dict(name):
    ours, theirs = clmesh.load(str(DATASETS), name), triangle.load(str(DATASETS), name)
    assert list(ours) == list(theirs)
    for key in ours:
        assert ours[key].dtype == theirs[key].dtype, key
        assert ours[key].shape == theirs[key].shape, key
        if key == "regions":
            # triangle.loads reads (x, y, 0, third value); clmesh as Triangle
            # does: the third value is the attribute, and the maximum area
            # when no fourth follows.
            assert np.array_equal(ours[key][:, [0, 1, 3]], theirs[key][:, [0, 1, 3]])
        else:
            assert np.array_equal(ours[key], theirs[key]), key


def test_loaded_mesh_refines_within_its_areas():
    # bbox.1: a mesh with its .area file; -ra bounds the triangles inside each
    # bounded one of the mesh (its .area's positive values) by its bound.
    mesh = clmesh.load(str(DATASETS), "bbox.1")
    assert mesh["triangle_max_area"].shape == (len(mesh["triangles"]), 1)
    refined = clmesh.run(mesh, "ra")
    assert refined.check() == []
    assert len(refined.mesh["triangles"]) > len(mesh["triangles"])
    points, triangles = refined.mesh["vertices"], refined.mesh["triangles"]
    corners = points[triangles]
    centroids = corners.mean(axis=1)
    edges = corners[:, 1:] - corners[:, :1]
    areas = 0.5 * np.abs(edges[:, 0, 0] * edges[:, 1, 1] - edges[:, 0, 1] * edges[:, 1, 0])
    given = mesh["vertices"][mesh["triangles"]]
    bounded = 0
    for (a, b, c), bound in zip(given, mesh["triangle_max_area"].ravel()):
        if bound <= 0:
            continue
        d = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
        u = ((centroids[:, 0] - a[0]) * (c[1] - a[1]) - (centroids[:, 1] - a[1]) * (c[0] - a[0])) / d
        v = ((b[0] - a[0]) * (centroids[:, 1] - a[1]) - (b[1] - a[1]) * (centroids[:, 0] - a[0])) / d
        inside = (u > 0) & (v > 0) & (u + v < 1)
        bounded += inside.sum()
        assert np.all(areas[inside] <= bound * (1 + 1e-9))
    assert bounded > 0


def test_loads_reads_strings_and_numbers_from_zero():
    node = "4 2 1 1\n1 0 0 5 1\n2 1 0 6 1\n3 1 1 7 2\n4 0 1 8 0  # comment\n"
    poly = "0 2 1 1\n2 1\n1 1 3 9\n2 2 4 0\n1\n1 0.1 0.9\n"
    ele = "2 3 1\n1 1 2 3 0.5\n2 1 3 4 0.25\n"
    area = "2\n1 0.1\n2 -1\n"
    data = clmesh.loads(node=node, poly=poly, ele=ele, area=area, edge="ignored")
    assert np.array_equal(data["vertices"], [[0, 0], [1, 0], [1, 1], [0, 1]])
    assert np.array_equal(data["vertex_attributes"], [[5], [6], [7], [8]])
    assert np.array_equal(data["vertex_markers"], [[1], [1], [2], [0]])
    assert np.array_equal(data["segments"], [[0, 2], [1, 3]])
    assert np.array_equal(data["segment_markers"], [[9], [0]])
    assert np.array_equal(data["holes"], [[0.1, 0.9]])
    assert np.array_equal(data["triangles"], [[0, 1, 2], [0, 2, 3]])
    assert np.array_equal(data["triangle_attributes"], [[0.5], [0.25]])
    assert np.array_equal(data["triangle_max_area"], [[0.1], [-1]])
    assert clmesh.loads() == {}


def test_loads_error_names_the_file_kind_and_line():
    with pytest.raises(clmesh.InputError, match=r"<poly>:6: endpoint 7 of segment 1"):
        clmesh.loads(poly="3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n1 0\n1 1 7\n")
    with pytest.raises(clmesh.InputError, match="no .node, .poly or .ele file"):
        clmesh.load(str(DATASETS), "no such input")
