"""clmesh against the triangle package (PyPI) on the same inputs: the same
triangles where the answer is unique, the same keys, shapes and dtypes, and
quality meshes of about the same size."""

import numpy as np
import pytest

import clmesh
from conftest import DATASETS, SHARED, load, random_points, triangle, triangle_set

# Inputs in general position (no four cocircular points, no three collinear
# ones where that would leave a choice), so that their Delaunay and
# constrained Delaunay triangulations are unique.
DELAUNAY_INPUTS = [
    (DATASETS, "dots"), (DATASETS, "spiral"), (DATASETS, "greenland"), (DATASETS, "A"),
    (DATASETS, "face"), (DATASETS, "la"), (DATASETS, "square_circle_hole"),
    (SHARED / "pslg", "water2"), (SHARED / "pslg", "island"), (SHARED / "pslg", "kidney"),
    (SHARED / "triangle-examples" / "inputs", "dots"),
]
CDT_INPUTS = [
    (DATASETS, "A"), (DATASETS, "face"), (DATASETS, "la"), (DATASETS, "double_hex"),
    (DATASETS, "square_circle_hole"), (SHARED / "pslg", "water2"),
    (SHARED / "pslg", "water4"), (SHARED / "pslg", "island"), (SHARED / "pslg", "butterfly"),
]


def ident(case):
    return f"{case[0].name}/{case[1]}"


@pytest.mark.parametrize("case", DELAUNAY_INPUTS, ids=ident)
def test_delaunay_triangles_match(case):
    data = {"vertices": load(*case)["vertices"]}
    ours, theirs = clmesh.triangulate(data), triangle.triangulate(data)
    assert triangle_set(ours["triangles"]) == triangle_set(theirs["triangles"])
    assert np.array_equal(ours["vertices"], theirs["vertices"])


@pytest.mark.parametrize("n, seed", [(3, 1), (50, 2), (5000, 3)])
def test_delaunay_of_random_points(n, seed):
    points = random_points(n, seed)
    assert triangle_set(clmesh.delaunay(points)) == triangle_set(triangle.delaunay(points))


def test_convex_hull_edges_match():
    points = random_points(500, 4)
    assert set(map(tuple, clmesh.convex_hull(points).tolist())) == set(
        map(tuple, triangle.convex_hull(points).tolist()))


@pytest.mark.parametrize("case", CDT_INPUTS, ids=ident)
def test_constrained_triangles_match(case):
    data = load(*case)
    ours, theirs = clmesh.triangulate(data, "p"), triangle.triangulate(data, "p")
    assert triangle_set(ours.get("triangles", [])) == triangle_set(theirs.get("triangles", []))
    assert len(ours.get("triangles", [])) > 0


def _describe(mesh):
    return {key: (value.dtype, value.shape) for key, value in mesh.items()}


@pytest.mark.parametrize("switches", [
    "", "e", "n", "en", "B", "eB", "N", "E", "j", "c", "p", "pc", "pe", "pn", "pB", "pcB", "pA",
    "pO", "pAen", "pj", "v", "pv", "o2", "po2", "pAeno2", "o2B", "o2N", "o2E"])
def test_same_keys_shapes_and_dtypes(switches):
    data = load(DATASETS, "la")  # markers, regions, segments; no Steiner points for these
    data["vertex_attributes"] = np.arange(len(data["vertices"]), dtype=float)
    ours, theirs = clmesh.triangulate(data, switches), triangle.triangulate(data, switches)
    assert _describe(ours) == _describe(theirs)
    assert list(ours) == list(theirs)  # the same key order too


def _marked(pairs, markers):
    """Edges or segments with their markers, as a set (order and direction ignored)."""
    return {tuple(sorted(pair)) + (marker,)
            for pair, marker in zip(pairs.tolist(), markers.ravel().tolist())}


@pytest.mark.parametrize("name", ["face", "la", "A", "square_circle_hole"])
@pytest.mark.parametrize("switches", ["", "e", "p", "pc", "pe", "pA"])
def test_markers_segments_and_attributes_match(name, switches):
    data = load(DATASETS, name)
    ours, theirs = clmesh.triangulate(data, switches), triangle.triangulate(data, switches)
    assert np.array_equal(ours["vertex_markers"], theirs["vertex_markers"])
    if "p" in switches:
        assert _marked(ours["segments"], ours["segment_markers"]) == _marked(
            theirs["segments"], theirs["segment_markers"])
    if "e" in switches:
        assert _marked(ours["edges"], ours["edge_markers"]) == _marked(
            theirs["edges"], theirs["edge_markers"])
    if "triangle_attributes" in theirs:
        attribute = {tuple(sorted(t)): a for t, a in zip(theirs["triangles"].tolist(),
                                                         theirs["triangle_attributes"].ravel())}
        assert [attribute[tuple(sorted(t))] for t in ours["triangles"].tolist()] == \
            ours["triangle_attributes"].ravel().tolist()


def test_crossings_repeated_segments_and_region_free_A_match():
    """Where two segments cross, the new vertex's attributes are interpolated
    along the first of them; a repeated segment's non-zero marker marks the
    segment; -A without regions adds no triangle attribute: all as Triangle."""
    data = {"vertices": np.array([[0, 0], [1, 0], [1, 1], [0, 1]], dtype=float),
            "vertex_attributes": np.array([[1, 10], [2, 20], [3, 30], [4, 40]], dtype=float),
            "segments": np.array([[0, 2], [1, 3], [2, 0]]),
            "segment_markers": np.array([[0], [0], [5]])}
    for switches in ["pc", "pcA", "pce"]:
        ours, theirs = clmesh.triangulate(data, switches), triangle.triangulate(data, switches)
        assert _describe(ours) == _describe(theirs)
        assert np.array_equal(ours["vertices"], theirs["vertices"])
        assert np.array_equal(ours["vertex_attributes"], theirs["vertex_attributes"])
        assert np.array_equal(ours["vertex_markers"], theirs["vertex_markers"])
        assert _marked(ours["segments"], ours["segment_markers"]) == _marked(
            theirs["segments"], theirs["segment_markers"])


@pytest.mark.parametrize("switches, area", [
    ("q", None), ("q30", None), ("a0.0002", 0.0002), ("q25a0.0005", 0.0005)])
def test_quality_mesh_of_points(switches, area):
    _compare_quality({"vertices": random_points(2000, 5)}, switches, area)


# -pq and -pa meshes of PSLGs with area bounds, so that counts are in the thousands.
@pytest.mark.parametrize("case, switches, area", [
    ((DATASETS, "square_circle_hole"), "pq30a0.015", 0.015),
    ((DATASETS, "face"), "pq30a6.7", 6.7),
    ((DATASETS, "double_hex"), "pq30a0.0003", 0.0003),
    ((DATASETS, "la"), "pq30a0.16", 0.16),
    ((SHARED / "pslg", "water2"), "pa2553", 2553),
], ids=lambda value: ident(value) if isinstance(value, tuple) else str(value))
def test_quality_mesh_of_pslg(case, switches, area):
    _compare_quality(load(*case), switches, area)


def _compare_quality(data, switches, area):
    """A valid mesh, the same keys as Triangle's, a vertex count within 5% of
    Triangle's, and no triangle above the area bound."""
    result = clmesh.run(data, switches)
    theirs = triangle.triangulate(data, switches)
    assert result.check() == []
    ours = result.mesh
    assert _describe(ours).keys() == _describe(theirs).keys()
    assert abs(len(ours["vertices"]) - len(theirs["vertices"])) <= 0.05 * len(theirs["vertices"])
    if area is not None:
        assert result.quality_statistics()["largest_area"] <= area * (1 + 1e-9)
