"""Bad input raises clmesh's exceptions with a clear message, and never
reaches the library in a state that could crash the interpreter."""

import numpy as np
import pytest

import clmesh

SQUARE = np.array([[0, 0], [1, 0], [1, 1], [0, 1], [0.5, 0.3]])


def test_error_classes():
    assert issubclass(clmesh.InputError, ValueError)
    assert issubclass(clmesh.OptionError, ValueError)
    for error in (clmesh.InputError, clmesh.OptionError, clmesh.DeviceError, clmesh.CheckError):
        assert issubclass(error, clmesh.Error)


@pytest.mark.parametrize("tri, message", [
    ({"vertices": SQUARE[:2]}, "at least three vertices"),
    ({"vertices": []}, "at least three vertices"),
    ({"vertices": np.zeros((5, 3))}, "vertices: expected shape"),
    ({"vertices": np.zeros(10)}, "vertices: expected shape"),
    ({"vertices": np.zeros((2, 5, 2))}, "vertices: expected shape"),
    ({"vertices": [["a", "b"], ["c", "d"], ["e", "f"]]}, "expected numbers"),
    ({"vertices": [[0, 0], [1, 0], [1]]}, "vertices"),
    ({"vertices": np.array([[0, 0], [1, 0], [np.nan, 1]])}, "not finite"),
    ({"vertices": np.array([[0, 0], [1, 0], [np.inf, 1]])}, "not finite"),
    ({"vertices": np.array([[0, 0], [1, 0], [1e300, 1]])}, "exact arithmetic"),
    ({"vertices": SQUARE, "segments": [[0, 5]]}, "out of range"),
    ({"vertices": SQUARE, "segments": [[-1, 2]]}, "out of range"),
    ({"vertices": SQUARE, "segments": [[0, 2**40]]}, "out of range"),
    ({"vertices": SQUARE, "segments": [[0, 1.5]]}, "expected integers"),
    ({"vertices": SQUARE, "segments": [[0, 1, 2]]}, "segments: expected shape"),
    ({"vertices": SQUARE, "segments": [[0, 1]], "segment_markers": [1, 2]}, "segment_markers"),
    ({"vertices": SQUARE, "vertex_markers": [1, 2, 3]}, "vertex_markers"),
    ({"vertices": SQUARE, "vertex_markers": [2**40] * 5}, "int32"),
    ({"vertices": SQUARE, "vertex_attributes": np.zeros((4, 2))}, "vertex_attributes"),
    ({"vertices": SQUARE, "holes": [[np.nan, 0]]}, "holes"),
    ({"vertices": SQUARE, "regions": [[0.5, 0.5, 1]]}, "regions: expected shape"),
    ({"vertices": SQUARE, "unknown": 1}, "unknown key"),
    ({"points": SQUARE}, "unknown key"),
    ({}, "'vertices' is missing"),
    ([[0, 0], [1, 0], [0, 1]], "expected a dict"),
])
def test_bad_input_raises_input_error(tri, message):
    with pytest.raises(clmesh.InputError, match=message):
        clmesh.triangulate(tri, "p")


@pytest.mark.parametrize("switches, message", [
    ("k", "unknown switch -k"),
    ("pq30x", "unknown switch -x"),
    ("u", "not supported yet"),
    ("qa", "needs -p"),
    ("a-1", "unknown switch --"),
    ("q50", "between 0 and 45"),
    ("q3k", "unknown switch -k"),
])
def test_bad_switches_raise_option_error(switches, message):
    with pytest.raises(clmesh.OptionError, match=message):
        clmesh.triangulate({"vertices": SQUARE}, switches)


def test_switches_must_be_a_string():
    with pytest.raises(clmesh.OptionError):
        clmesh.triangulate({"vertices": SQUARE}, 30)


def test_unknown_device_raises_device_error():
    with pytest.raises(clmesh.DeviceError):
        clmesh.triangulate({"vertices": SQUARE}, "", device="no such device anywhere")


def test_quality_statistics_checks_indices():
    with pytest.raises(clmesh.InputError, match="out of range"):
        clmesh.quality_statistics({"vertices": SQUARE, "triangles": [[0, 1, 9]]})


def _garbage(rng, n):
    """A random array-like: any shape up to 3-D, any dtype, odd values."""
    kind = rng.integers(6)
    shape = tuple(int(rng.integers(0, 4 if d else n + 2)) for d in range(rng.integers(0, 4)))
    if kind == 0:
        return rng.normal(size=shape) * 10.0 ** rng.integers(-60, 60)
    if kind == 1:
        return rng.integers(-3, n + 3, size=shape)
    if kind == 2:
        return np.full(shape, rng.choice([np.nan, np.inf, -np.inf, 1e308, 0.0]))
    if kind == 3:
        return rng.integers(-2**62, 2**62, size=shape, dtype=np.int64)
    if kind == 4:
        return [["x"] * 2] * n
    return None


def test_random_garbage_raises_clmesh_errors_only():
    rng = np.random.default_rng(29)
    keys = ["vertex_markers", "vertex_attributes", "segments", "segment_markers", "holes",
            "regions"]
    for case in range(300):
        n = int(rng.integers(0, 8))
        tri = {"vertices": rng.random((n, 2)) if rng.random() < 0.7 else _garbage(rng, n)}
        for key in rng.choice(keys, size=int(rng.integers(0, 4)), replace=False):
            tri[str(key)] = _garbage(rng, n)
        try:
            mesh = clmesh.triangulate(tri, str(rng.choice(["", "p", "pc", "pA", "q", "en"])))
        except clmesh.Error:
            continue
        assert mesh["vertices"].shape[1] == 2, case
