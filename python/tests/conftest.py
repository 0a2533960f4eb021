"""Shared fixtures: where the bundled and shared inputs are, and how to read them."""

import pathlib

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
DATASETS = ROOT / "datasets"
# Shared reference data lives beside the repository; tests that need it skip
# when it is absent.
SHARED = ROOT.parent / "shared" / "data"

triangle = pytest.importorskip("triangle")


def load(folder, name):
    """A Triangle .node/.poly input as the triangle package's dict."""
    folder = pathlib.Path(folder)
    if not folder.is_dir():
        pytest.skip(f"{folder} is absent")
    return triangle.load(str(folder), name)


def triangle_set(triangles):
    """Triangles as a set of sorted vertex triples (order and rotation ignored)."""
    return {tuple(sorted(row)) for row in np.asarray(triangles).tolist()}


def random_points(n, seed):
    return np.random.default_rng(seed).random((n, 2))
