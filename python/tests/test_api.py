"""The rest of the API: devices, statistics, quality statistics, the exact
check, -j, determinism, the version."""

import importlib.metadata
import json
import os
import re
import subprocess
import sys

import numpy as np
import pytest

import clmesh
from conftest import DATASETS, ROOT, load, random_points, triangle, triangle_set


def test_version_matches_cmake_project():
    cmake = (ROOT / "CMakeLists.txt").read_text()
    assert re.search(r"project\(clmesh VERSION ([0-9.]+)", cmake).group(1) == clmesh.__version__
    assert importlib.metadata.version("clmesh") == clmesh.__version__


def test_devices_and_device_argument():
    devices = clmesh.devices()
    usable = [d for d in devices if d["fp64"]]
    assert usable, "no OpenCL device with fp64"
    assert all(isinstance(d["cpu"], bool) for d in devices)
    # PoCL's devices, which the tests run on, are CPUs.
    assert all(d["cpu"] for d in devices if d["platform"] == "Portable Computing Language")
    points = {"vertices": random_points(300, 21)}
    default = clmesh.triangulate(points)
    for device in (usable[0], usable[0]["spec"], 0):
        assert np.array_equal(clmesh.triangulate(points, device=device)["triangles"],
                              default["triangles"])


def test_device_from_environment():
    # CLMESH_DEVICE names the default device; it is read when a process first
    # opens it, so each case runs in a process of its own.
    script = ("import clmesh\n"
              "try:\n"
              "    clmesh.triangulate({'vertices': [[0, 0], [1, 0], [0, 1]]})\n"
              "    print('ok')\n"
              "except clmesh.DeviceError as error:\n"
              "    print('DeviceError', error)\n")
    def outcome(spec):
        env = dict(os.environ, CLMESH_DEVICE=spec)
        return subprocess.run([sys.executable, "-c", script], env=env, capture_output=True,
                              text=True, check=True).stdout
    usable = next(d for d in clmesh.devices() if d["fp64"])
    assert outcome(usable["spec"]) == "ok\n"
    assert outcome("no such device anywhere").startswith("DeviceError")


def test_statistics_have_the_stats_json_keys():
    data = load(DATASETS, "face")
    plain = clmesh.run(data, "").statistics()
    assert {"device", "seconds", "phases", "counts"} <= plain.keys()
    assert "constraints" not in plain and "refinement" not in plain
    assert plain["counts"]["input_points"] == len(data["vertices"])
    constrained = clmesh.statistics(clmesh.run(data, "p"))
    assert "constraints" in constrained
    refined = clmesh.run(data, "pq30a6.7")
    stats = refined.statistics()
    assert stats["refinement"]["steiner_points"] == len(refined.mesh["vertices"]) - len(
        data["vertices"])
    assert stats["counts"]["triangles"] == len(refined.mesh["triangles"])


def _key_tree(value):
    """The keys of a JSON value, nested (list items by their first one)."""
    if isinstance(value, dict):
        return {key: _key_tree(item) for key, item in value.items()}
    if isinstance(value, list):
        return [_key_tree(value[0])] if value else []
    return None


@pytest.mark.parametrize("name, switches", [
    ("dots.node", ""), ("dots.node", "-q"), ("face.poly", "-p"), ("face.poly", "-pq30a6.7")])
def test_statistics_keys_equal_the_command_lines(name, switches, tmp_path):
    cli = ROOT / "build" / "clmesh"
    if not cli.exists():
        pytest.skip("the command line is not built (build/clmesh)")
    (tmp_path / name).write_bytes((DATASETS / name).read_bytes())
    stats = tmp_path / "stats.json"
    subprocess.run([str(cli), "-Q", *([switches] if switches else []), "--stats-json",
                    str(stats), str(tmp_path / name)], check=True)
    ours = clmesh.run(load(DATASETS, name.split(".")[0]), switches).statistics()
    assert _key_tree(ours) == _key_tree(json.loads(stats.read_text()))


def test_quality_statistics_equal_triangles_on_the_same_mesh():
    points = {"vertices": random_points(2000, 22)}
    ours, theirs = clmesh.run(points, ""), triangle.triangulate(points)
    assert ours.quality_statistics() == clmesh.quality_statistics(theirs)
    quality = clmesh.quality_statistics(ours.mesh)
    assert quality["triangles"] == len(ours.mesh["triangles"])
    assert sum(quality["angle_histogram"]) == 3 * quality["triangles"]


def test_quality_mesh_meets_its_angle():
    result = clmesh.run({"vertices": random_points(2000, 23)}, "q30")
    # Triangle's rule: only angles at hull vertices may stay below the bound.
    assert result.quality_statistics()["smallest_angle"] > 0
    assert result.check() == []


def test_check_mesh_finds_nothing_in_valid_meshes():
    for switches in ("", "p", "pc", "q", "pq30a0.015"):
        result = clmesh.run(load(DATASETS, "square_circle_hole"), switches)
        assert clmesh.check_mesh(result) == []
    assert clmesh.triangulate({"vertices": random_points(100, 24)}, "C")["triangles"].size


def test_jettison_drops_duplicates_and_renumbers():
    points = random_points(50, 25)
    doubled = np.concatenate([points, points[:10]])
    theirs = triangle.triangulate({"vertices": doubled}, "j")
    ours = clmesh.triangulate({"vertices": doubled}, "j")
    assert len(ours["vertices"]) == len(theirs["vertices"]) == 50
    # Which copy of a duplicate stays is the mesher's choice: compare places.
    assert _corner_set(ours) == _corner_set(theirs)
    without = clmesh.triangulate({"vertices": doubled})
    assert len(without["vertices"]) == 60 and without["triangles"].max() < 50


def _corner_set(mesh):
    corners = mesh["vertices"][mesh["triangles"]]
    return {tuple(sorted(map(tuple, corner.tolist()))) for corner in corners}


def test_same_input_same_output():
    data = load(DATASETS, "la")
    first, second = clmesh.triangulate(data, "pq20a0.3e"), clmesh.triangulate(data, "pq20a0.3e")
    assert first.keys() == second.keys()
    assert all(np.array_equal(first[k], second[k]) for k in first)


def test_inputs_of_any_numeric_dtype_and_lists():
    points = random_points(100, 26)
    expected = clmesh.delaunay(points)
    assert np.array_equal(clmesh.delaunay(points.tolist()), expected)
    assert np.array_equal(clmesh.delaunay(np.asfortranarray(points)), expected)
    grid = np.array([[0, 0], [3, 0], [0, 3], [3, 3], [1, 2]], dtype=np.int64)
    assert clmesh.triangulate({"vertices": grid})["vertices"].dtype == np.float64
    float32 = points.astype(np.float32)
    assert np.array_equal(clmesh.delaunay(float32), clmesh.delaunay(float32.astype(float)))


def test_import_as_triangle_runs_triangle_code():
    import clmesh as tr
    v = [[0, 0], [0, 1], [1, 1], [1, 0]]
    t = tr.triangulate({"vertices": v}, "a0.2")
    assert t["vertices"].shape[1] == 2 and t["vertex_markers"].shape[1] == 1
    assert t["triangles"].dtype == np.int32
