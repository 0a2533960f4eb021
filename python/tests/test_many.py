"""triangulate_many(): many dicts in one call give, input by input, what a
loop of triangulate() gives; a failed input's error is raised (the first
one) or put in its place, naming the input."""

import concurrent.futures

import numpy as np
import pytest

import clmesh
from conftest import DATASETS, load, random_points


def same(a, b):
    """Two output dicts with the same keys, in the same order, and equal arrays."""
    return list(a) == list(b) and all(
        a[k].dtype == b[k].dtype and np.array_equal(a[k], b[k]) for k in a)


def point_sets():
    lattice = np.stack(np.meshgrid(np.arange(9.0), np.arange(7.0)), -1).reshape(-1, 2)
    repeated = np.concatenate([random_points(50, 3), random_points(50, 3)[:10]])
    return [{"vertices": random_points(n, seed)} for n, seed in ((400, 1), (3, 2), (1500, 4))] + [
        {"vertices": lattice, "vertex_markers": np.arange(len(lattice))},
        {"vertices": repeated, "vertex_attributes": np.arange(len(repeated) * 2.0).reshape(-1, 2)},
    ]


def pslgs():
    return [load(DATASETS, name) for name in ("square_circle_hole", "la", "A", "face", "box")]


def meshes_to_refine():
    """Meshes as triangulate() returns them, with attributes, to refine with -r."""
    out = []
    for seed, tri in enumerate(point_sets()[:1] + pslgs()[:3]):
        mesh = clmesh.triangulate(tri, "pA" if "segments" in tri else "")
        count = len(mesh["triangles"])
        mesh["triangle_attributes"] = np.arange(count, dtype=float).reshape(-1, 1)
        mesh["triangle_max_area"] = np.random.default_rng(seed).uniform(0.05, 0.5, count)
        out.append(mesh)
    return out


CASES = [
    (point_sets, ""), (point_sets, "q30ez"), (point_sets, "nBj"),
    (pslgs, "pq30"), (pslgs, "pcAen"), (pslgs, "pq30a0.5o2"),
    (meshes_to_refine, "rq30"), (meshes_to_refine, "rpa"), (meshes_to_refine, "rq25a0.2e"),
]


@pytest.mark.parametrize("inputs, switches", CASES)
def test_the_results_are_those_of_a_loop_of_triangulate(inputs, switches):
    tris = inputs()
    alone = [clmesh.triangulate(tri, switches) for tri in tris]
    many = clmesh.triangulate_many(tris, switches)
    assert len(many) == len(tris)
    for mesh, expected in zip(many, alone):
        assert same(mesh, expected)
    # A tuple, a generator: any iterable of dicts.
    again = clmesh.triangulate_many((tri for tri in tris), switches, errors="return")
    assert all(same(mesh, expected) for mesh, expected in zip(again, alone))


def test_size_field_and_unsuitable_serve_every_input():
    field = {"vertices": [[0, 0], [20, 0], [20, 20], [0, 20]],
             "triangles": [[0, 1, 2], [0, 2, 3]], "area": [0.5, 0.05, 0.5, 0.05]}
    squares = [{"vertices": np.array([[0, 0], [1, 0], [1, 1], [0, 1]]) * s + s,
                "segments": [[0, 1], [1, 2], [2, 3], [3, 0]]} for s in (1, 3, 5)]
    by_field = clmesh.triangulate_many(squares, "pq30", size_field=field)
    for tri, mesh in zip(squares, by_field):
        assert same(mesh, clmesh.triangulate(tri, "pq30", size_field=field))

    def unsuitable(a, b, c, area):
        return area > 0.01 * (a[0] + b[0] + c[0]) / 3

    by_function = clmesh.triangulate_many(squares, "pq30", unsuitable=unsuitable)
    for tri, mesh in zip(squares, by_function):
        assert same(mesh, clmesh.triangulate(tri, "pq30", unsuitable=unsuitable))
        corners = mesh["vertices"][mesh["triangles"]]
        u, v = corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]
        areas = (u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]) / 2
        assert (areas <= 0.01 * corners[:, :, 0].mean(axis=1)).all()


def error_of(tri, switches):
    with pytest.raises(clmesh.Error) as caught:
        clmesh.triangulate(tri, switches)
    return caught.value


# Input 1 cannot be converted (two vertices); input 3 fails in the library (a
# clockwise triangle to refine); the others are meshed.
SQUARE = np.array([[0, 0], [1, 0], [1, 1], [0, 1], [0.5, 0.25]])
GOOD = {"vertices": SQUARE, "triangles": [[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]]}
MIXED = [GOOD, {"vertices": SQUARE[:2]}, dict(GOOD, vertices=SQUARE * 2),
         dict(GOOD, triangles=[[0, 4, 1]]), dict(GOOD, vertices=SQUARE * 3)]


def test_errors_return_puts_each_error_in_its_place():
    results = clmesh.triangulate_many(MIXED, "rq30a0.1", errors="return")
    assert len(results) == len(MIXED)
    for index in (0, 2, 4):
        assert same(results[index], clmesh.triangulate(MIXED[index], "rq30a0.1"))
    for index in (1, 3):
        alone = error_of(MIXED[index], "rq30a0.1")
        error = results[index]
        assert type(error) is type(alone) is clmesh.InputError
        assert str(error) == f"input {index}: {alone}"
        assert error.index == index
    assert "clockwise" in str(results[3])


def test_errors_raise_raises_a_bad_dict_before_meshing():
    calls = []

    def unsuitable(a, b, c, area):
        calls.append(area)
        return False

    with pytest.raises(clmesh.InputError, match="^input 1: input must have at least three") as e:
        clmesh.triangulate_many(MIXED, "rq30a0.1", unsuitable=unsuitable)
    assert e.value.index == 1
    assert calls == []  # input 0 was not meshed


def test_errors_raise_stops_at_the_first_failed_input():
    # A callback that knows each input by its x offset (10 per input) and
    # fails on input 1.
    class Failed(Exception):
        pass

    raised, meshed = [], set()

    def unsuitable(a, b, c, area):
        index = int(a[0] // 10)
        meshed.add(index)
        if index == 1:
            raised.append(Failed("input 1 cannot be sized"))
            raise raised[-1]
        return area > 0.02

    squares = [{"vertices": SQUARE + [10 * i, 0]} for i in range(4)]
    with pytest.raises(Failed) as caught:
        clmesh.triangulate_many(squares, "q30", unsuitable=unsuitable)
    assert caught.value is raised[0] and caught.value.index == 1
    assert meshed == {0, 1}
    # errors="return": the same object in its place, and every other input meshed.
    meshed.clear()
    results = clmesh.triangulate_many(squares, "q30", unsuitable=unsuitable, errors="return")
    assert results[1] is raised[-1] and results[1].index == 1
    assert meshed == {0, 1, 2, 3}
    for index in (0, 2, 3):
        assert same(results[index], clmesh.triangulate(squares[index], "q30",
                                                       unsuitable=unsuitable))


def test_keyboard_interrupt_ends_the_batch_in_both_modes():
    meshed = set()

    def unsuitable(a, b, c, area):
        meshed.add(int(a[0] // 10))
        if a[0] >= 10:
            raise KeyboardInterrupt
        return False

    squares = [{"vertices": SQUARE + [10 * i, 0]} for i in range(3)]
    for errors in ("raise", "return"):
        meshed.clear()
        with pytest.raises(KeyboardInterrupt):
            clmesh.triangulate_many(squares, "q", unsuitable=unsuitable, errors=errors)
        assert meshed == {0, 1}


def test_an_empty_list_gives_an_empty_list():
    assert clmesh.triangulate_many([]) == []
    assert clmesh.triangulate_many([], "pq30", errors="return") == []


@pytest.mark.parametrize("call, error, message", [
    (lambda: clmesh.triangulate_many([GOOD], "rq30x"), clmesh.OptionError, "x"),
    # Bad switches are the batch's error, before any input's.
    (lambda: clmesh.triangulate_many(MIXED, "a"), clmesh.OptionError, "-a"),
    (lambda: clmesh.triangulate_many([], "a"), clmesh.OptionError, "-a"),
    (lambda: clmesh.triangulate_many([GOOD], errors="ignore"), clmesh.OptionError,
     "errors: expected 'raise' or 'return'"),
    (lambda: clmesh.triangulate_many(GOOD), clmesh.InputError, "expected a list of dicts"),
    (lambda: clmesh.triangulate_many([GOOD, [[0, 0]]], errors="return"), None, None),
    (lambda: clmesh.triangulate_many([GOOD], device="no such device"), clmesh.DeviceError,
     "no such device"),
    (lambda: clmesh.triangulate_many([GOOD], unsuitable=1), clmesh.OptionError, "unsuitable"),
])
def test_bad_arguments(call, error, message):
    if error is None:
        # A list instead of a dict is that input's error.
        results = call()
        assert isinstance(results[1], clmesh.InputError) and results[1].index == 1
        assert str(results[1]).startswith("input 1: expected a dict")
        return
    with pytest.raises(error, match=message):
        call()


def test_an_unsuitable_function_cannot_mesh_a_batch():
    def unsuitable(a, b, c, area):
        clmesh.triangulate_many([GOOD])
        return False

    results = clmesh.triangulate_many([{"vertices": SQUARE}], "q", unsuitable=unsuitable,
                                      errors="return")
    assert isinstance(results[0], clmesh.Error)
    assert "called from an unsuitable function" in str(results[0])


def test_batches_and_calls_from_threads_give_the_serial_results():
    tris = point_sets() + pslgs()
    switches = ["q30"] * len(point_sets()) + ["pq30"] * len(pslgs())
    serial = [clmesh.triangulate(tri, s) for tri, s in zip(tris, switches)]
    points, polys = len(point_sets()), slice(len(point_sets()), None)
    with concurrent.futures.ThreadPoolExecutor(max_workers=4) as pool:
        batches = [pool.submit(clmesh.triangulate_many, tris[:points], "q30"),
                   pool.submit(clmesh.triangulate_many, tris[polys], "pq30")]
        singles = [pool.submit(clmesh.triangulate, tri, s) for tri, s in zip(tris, switches)]
        many = batches[0].result() + batches[1].result()
        for mesh, single, expected in zip(many, singles, serial):
            assert same(mesh, expected)
            assert same(single.result(), expected)


@pytest.mark.parametrize("switches", ["pq30", "q30ez"])
def test_streams_give_the_results_of_a_loop(switches):
    # PoCL's multi-threaded device takes streams (its in-thread one, which
    # small inputs get by default, takes one).
    device = "pthread" if any("pthread" in d["name"] for d in clmesh.devices()) else None
    tris = (pslgs() if switches.startswith("p") else point_sets()) * 3
    alone = [clmesh.triangulate(tri, switches, device) for tri in tris]
    many = clmesh.triangulate_many(tris, switches, device, streams=3, errors="return")
    assert len(many) == len(tris)
    for mesh, expected in zip(many, alone):
        assert same(mesh, expected)
    with pytest.raises(clmesh.OptionError, match="streams"):
        clmesh.triangulate_many(tris, switches, streams=0)
