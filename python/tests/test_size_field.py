"""Size control beyond -a: triangulate(size_field=..., unsuitable=...).

A background mesh's target areas, interpolated here independently with
NumPy, must bound every triangle at its centroid and grade the mesh; a
callback that asks what the field asks must give the same mesh; what a
callback raises must reach the caller unchanged, from any thread; bad fields
raise InputError.
"""

import concurrent.futures
import math

import numpy as np
import pytest

import clmesh

# The unit square with two inner points, as a PSLG (and with -p off, a point set).
SQUARE = {
    "vertices": [[0, 0], [1, 0], [1, 1], [0, 1], [0.31, 0.47], [0.62, 0.23]],
    "segments": [[0, 1], [1, 2], [2, 3], [3, 0]],
    "segment_markers": [1, 1, 1, 1],
}


def halving_field(left):
    """Over the unit square: `left` at x = 0, half of it at x = 1 (two
    background triangles, so linear in x)."""
    return {
        "vertices": np.array([[0, 0], [1, 0], [1, 1], [0, 1]], np.float64),
        "area": np.array([left, left / 2, left / 2, left]),
        "triangles": np.array([[0, 1, 2], [0, 2, 3]], np.int32),
    }


def interpolate(field, points):
    """The field at each point: linear over the background triangle whose
    smallest barycentric coordinate of the point is largest (the one holding
    it, or the nearest), negative coordinates clamped to zero."""
    corners = np.asarray(field["vertices"], np.float64)[field["triangles"]]  # (M, 3, 2)
    a, b, c = corners[:, 0], corners[:, 1], corners[:, 2]
    p = np.asarray(points, np.float64)[:, None, :]  # (K, 1, 2)

    def cross(u, v, w):
        return (v[..., 0] - u[..., 0]) * (w[..., 1] - u[..., 1]) - \
               (v[..., 1] - u[..., 1]) * (w[..., 0] - u[..., 0])

    twice = cross(a, b, c)
    weights = np.stack([cross(p, b, c), cross(a, p, c), cross(a, b, p)], axis=-1) / twice[:, None]
    best = weights.min(axis=-1).argmax(axis=1)  # (K,)
    w = np.clip(weights[np.arange(len(best)), best], 0, None)  # (K, 3)
    values = np.asarray(field["area"], np.float64)[field["triangles"][best]]
    return (w * values).sum(axis=1) / w.sum(axis=1)


def centroids_and_areas(mesh):
    corners = mesh["vertices"][mesh["triangles"]]
    a, b, c = corners[:, 0], corners[:, 1], corners[:, 2]
    areas = np.abs((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) -
                   (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])) / 2
    return corners.mean(axis=1), areas


def check_meets_field(mesh, field, graded=True):
    centres, areas = centroids_and_areas(mesh)
    wanted = interpolate(field, centres)
    too_large = np.flatnonzero(areas > wanted * (1 + 1e-9))
    assert too_large.size == 0, f"triangles larger than the field: {too_large[:10]}"
    if graded:
        left, right = areas[centres[:, 0] < 0.25], areas[centres[:, 0] > 0.75]
        assert left.size and right.size
        assert left.mean() > 1.3 * right.mean()


def field_callback(field, calls=None):
    """unsuitable() that asks what `field` asks: true when the triangle's area
    exceeds the field at its centroid, in the library's arithmetic
    (clmesh::size_at), so that the answers are the device's to the bit."""
    points = np.asarray(field["vertices"], np.float64).tolist()
    values = np.asarray(field["area"], np.float64).tolist()
    triangles = np.asarray(field["triangles"]).tolist()

    def at(x, y):
        best, value = -math.inf, 0.0
        for i, j, k in triangles:
            (ax, ay), (bx, by), (cx, cy) = points[i], points[j], points[k]
            twice = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax)
            l0 = ((bx - x) * (cy - y) - (by - y) * (cx - x)) / twice
            l1 = ((cx - x) * (ay - y) - (cy - y) * (ax - x)) / twice
            l2 = 1 - l0 - l1
            score = min(l0, l1, l2)
            if score > best:
                best = score
                w0, w1, w2 = max(l0, 0.0), max(l1, 0.0), max(l2, 0.0)
                value = (w0 * values[i] + w1 * values[j] + w2 * values[k]) / (w0 + w1 + w2)
        return value

    def unsuitable(a, b, c, area):
        if calls is not None:
            calls.append(area)
        return area > at((a[0] + b[0] + c[0]) / 3, (a[1] + b[1] + c[1]) / 3)

    return unsuitable


def same(a, b):
    return a.keys() == b.keys() and all(np.array_equal(a[k], b[k]) for k in a)


def test_the_test_interpolation_is_the_halving_field():
    points = np.random.default_rng(5).random((200, 2))
    assert np.allclose(interpolate(halving_field(0.002), points), 0.002 * (1 - points[:, 0] / 2))


@pytest.mark.parametrize("switches", ["", "q30", "p", "pq25"])
def test_every_triangle_meets_the_field_at_its_centroid(switches):
    field = halving_field(0.002)
    result = clmesh.run(SQUARE, switches, size_field=field)
    assert result.check() == []
    assert result.statistics()["refinement"]["stop_reason"] == "done"
    # About the square's area over the field's mean (0.0015) at least.
    assert len(result.mesh["triangles"]) > 600
    check_meets_field(result.mesh, field)


def test_the_field_and_a_global_area_bound_both_hold():
    field = halving_field(0.002)
    mesh = clmesh.triangulate(SQUARE, "pq30a0.0012", size_field=field)
    _, areas = centroids_and_areas(mesh)
    assert areas.max() <= 0.0012 * (1 + 1e-9)
    check_meets_field(mesh, field, graded=False)


@pytest.mark.parametrize("switches", ["q25", "pq30"])
def test_a_callback_that_asks_what_the_field_asks_gives_the_same_mesh(switches):
    field = halving_field(0.004)
    calls = []
    expected = clmesh.triangulate(SQUARE, switches, size_field=field)
    mesh = clmesh.triangulate(SQUARE, switches, unsuitable=field_callback(field, calls))
    assert same(mesh, expected)
    assert len(calls) >= len(mesh["triangles"])
    check_meets_field(mesh, field)


def test_the_callback_gets_tuples_of_corners_and_the_area():
    seen = []

    def unsuitable(a, b, c, area):
        seen.append((a, b, c, area))
        return np.float64(area) > 0.01  # a NumPy bool is an answer too

    mesh = clmesh.triangulate(SQUARE, "p", unsuitable=unsuitable)
    assert seen
    for a, b, c, area in seen:
        for corner in (a, b, c):
            assert type(corner) is tuple and len(corner) == 2
            assert all(type(x) is float for x in corner)
        twice = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
        assert twice > 0  # counter-clockwise
        assert type(area) is float and area == pytest.approx(twice / 2, rel=1e-12)
    _, areas = centroids_and_areas(mesh)
    assert areas.max() <= 0.01


class EstimateFailed(Exception):
    pass


def failing_after(count, raised):
    calls = []

    def unsuitable(a, b, c, area):
        calls.append(area)
        if len(calls) > count:
            error = EstimateFailed("the solver's estimate failed")
            raised.append(error)
            raise error
        return True

    return unsuitable


def test_what_the_callback_raises_reaches_the_caller_unchanged():
    raised = []
    with pytest.raises(EstimateFailed, match="^the solver's estimate failed$") as caught:
        clmesh.triangulate(SQUARE, "pq", unsuitable=failing_after(5, raised))
    assert len(raised) == 1 and caught.value is raised[0]
    # The answer's truth test failing is the callback's error too.
    with pytest.raises(ValueError, match="truth value of an array"):
        clmesh.triangulate(SQUARE, "pq", unsuitable=lambda a, b, c, area: np.array([True, False]))
    # The device is still usable.
    assert len(clmesh.triangulate(SQUARE, "pq")["triangles"]) > 0


def test_a_callback_that_meshes_again_raises_instead_of_waiting_forever():
    def unsuitable(a, b, c, area):
        clmesh.triangulate(SQUARE, "p")
        return False

    with pytest.raises(clmesh.Error, match="called from an unsuitable function"):
        clmesh.triangulate(SQUARE, "p", unsuitable=unsuitable)
    # Once the run has ended, the thread meshes again.
    assert len(clmesh.triangulate(SQUARE, "p")["triangles"]) > 0


def test_callbacks_from_several_threads_give_the_serial_results():
    cases = [("q30", 0.004, False), ("pq30", 0.003, True), ("pq25", 0.006, False),
             ("p", 0.005, True), ("q", 0.0035, False), ("pq20", 0.0045, True)]

    def mesh(switches, left, by_field):
        field = halving_field(left)
        if by_field:
            return clmesh.triangulate(SQUARE, switches, size_field=field)
        return clmesh.triangulate(SQUARE, switches, unsuitable=field_callback(field))

    serial = [mesh(*case) for case in cases]
    with concurrent.futures.ThreadPoolExecutor(max_workers=4) as pool:
        for _ in range(2):
            raised = []
            failing = pool.submit(clmesh.triangulate, SQUARE, "pq",
                                  unsuitable=failing_after(20, raised))
            futures = [pool.submit(mesh, *case) for case in cases]
            for future, expected in zip(futures, serial):
                assert same(future.result(), expected)
            assert failing.exception() is raised[0]


def test_a_mesh_refined_with_a_field_from_a_mesh_dict():
    # The background: a clmesh mesh (its other keys ignored) with an area added.
    # It covers the square: a larger square's corners and points inside it.
    corners = [[-0.1, -0.1], [1.1, -0.1], [1.1, 1.1], [-0.1, 1.1]]
    inside = np.random.default_rng(3).random((36, 2)) * 1.2 - 0.1
    background = clmesh.triangulate({"vertices": np.concatenate([corners, inside])}, "c")
    x = background["vertices"][:, 0]
    background["area"] = 0.004 * (1 - x / 2)
    mesh = clmesh.triangulate(SQUARE, "p")
    refined = clmesh.triangulate(mesh, "rpq25", size_field=background)
    assert len(refined["triangles"]) > 4 * len(mesh["triangles"])
    check_meets_field(refined, background)


def _with(**changes):
    field = halving_field(0.01)
    field.update(changes)
    return {key: value for key, value in field.items() if value is not None}


BAD_FIELDS = [
    (_with(area=[0.01, 0.005, 0, 0.01]), "size field: point 2: the target area must be positive"),
    (_with(area=[0.01, -1, 0.005, 0.01]), "size field: point 1: the target area must be positive"),
    (_with(area=[0.01, 0.005, np.nan, 0.01]), "size_field: area: row 2 is not finite"),
    (_with(area=[0.01, 0.005, 0.005]), "size_field: area: 3 rows, expected 4"),
    (_with(triangles=[[0, 1, 2], [0, 3, 2]]),
     "size field: triangle 1: its corners are not in counter-clockwise order"),
    (_with(triangles=[[0, 1, 2], [0, 2, 7]]), r"size_field: triangles: row 1 \(\[0, 2, 7\]\)"),
    (_with(triangles=np.zeros((0, 3), np.int32)), "the background mesh has no triangle"),
    (_with(vertices=[[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]),
     r"size_field: vertices: expected shape \(N, 2\)"),
    (_with(area=None), "size_field: 'area' is missing"),
    (_with(sizes=[1, 2, 3, 4]), "size_field: unknown key 'sizes'"),
    ([[0, 0], [1, 0], [1, 1]], "size_field: expected a dict"),
]


@pytest.mark.parametrize("field, message", BAD_FIELDS)
def test_bad_fields_raise_input_error(field, message):
    with pytest.raises(clmesh.InputError, match=message):
        clmesh.triangulate(SQUARE, "pq", size_field=field)


def test_an_unsuitable_that_is_not_callable_raises_option_error():
    with pytest.raises(clmesh.OptionError, match="unsuitable: expected a function"):
        clmesh.triangulate(SQUARE, "pq", unsuitable=0.01)
