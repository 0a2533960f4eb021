"""Calls from several threads at once give the results of serial calls."""

import concurrent.futures

import numpy as np

import clmesh
from conftest import DATASETS, load, random_points

SWITCHES = ["", "q30", "pq30a0.015", "pe"]


def _inputs():
    return [
        {"vertices": random_points(3000, 11)},
        {"vertices": random_points(1000, 12)},
        load(DATASETS, "square_circle_hole"),
        load(DATASETS, "la"),
    ]


def _same(a, b):
    return a.keys() == b.keys() and all(np.array_equal(a[k], b[k]) for k in a)


def test_four_threads_give_the_serial_results():
    inputs = _inputs()
    serial = [clmesh.triangulate(tri, s) for tri, s in zip(inputs, SWITCHES)]
    with concurrent.futures.ThreadPoolExecutor(max_workers=4) as pool:
        for _ in range(3):
            futures = [pool.submit(clmesh.triangulate, tri, s)
                       for tri, s in zip(inputs, SWITCHES)]
            for future, expected in zip(futures, serial):
                assert _same(future.result(), expected)


def test_errors_in_threads_do_not_disturb_others():
    good = {"vertices": random_points(500, 13)}
    expected = clmesh.triangulate(good)
    with concurrent.futures.ThreadPoolExecutor(max_workers=4) as pool:
        bad = {"vertices": good["vertices"][:2]}
        futures = [pool.submit(clmesh.triangulate, good if i % 2 else bad) for i in range(8)]
        for i, future in enumerate(futures):
            if i % 2:
                assert _same(future.result(), expected)
            else:
                assert isinstance(future.exception(), clmesh.InputError)
