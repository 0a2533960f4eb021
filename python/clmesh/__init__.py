"""clmesh: 2D Delaunay, constrained Delaunay and quality meshes on OpenCL.

A drop-in for the triangle package (``import clmesh as triangle``)::

    import clmesh
    mesh = clmesh.triangulate(dict(vertices=points, segments=segments), "pq30")
    meshes = clmesh.triangulate_many([tri_a, tri_b, tri_c], "pq30")

Dictionaries, keys, dtypes and zero-based indices are the triangle
package's; the switches are Triangle's letters as the clmesh command line
takes them (``z`` is implied, as there). Meshing runs with the GIL released, on one
OpenCL context per process and device whose built kernels serve every call
(and every input of a batch).
"""

import json

from . import _clmesh
from ._errors import (CheckError, DeviceError, Error, InputError, InternalError, OpenCLError,
                      OptionError)
from ._files import load, loads
from ._input import arrays as _arrays
from ._output import mesh_dict as _mesh_dict
from ._size_field import size_field as _size_field

__version__ = _clmesh.version

__all__ = [
    "triangulate", "triangulate_many", "delaunay", "convex_hull", "voronoi", "run", "Result", "devices",
    "statistics", "quality_statistics", "check_mesh", "Error", "InputError", "OptionError",
    "DeviceError", "OpenCLError", "InternalError", "CheckError", "load", "loads",
]


def devices():
    """The OpenCL devices: dicts with spec ("P:D", for device=), platform,
    name, version, fp64 (clmesh needs double precision) and cpu (whether it
    is a CPU device)."""
    return _clmesh.devices()


def _device_spec(device):
    if device is None:
        return ""  # $CLMESH_DEVICE, else the first device with fp64
    if isinstance(device, dict):
        return device["spec"]
    if isinstance(device, bool) or not isinstance(device, (str, int)):
        raise DeviceError(f"device: expected a spec string, an index or a devices() entry, "
                          f"got {device!r}")
    return str(device)


def _switches(opts):
    if not isinstance(opts, str):
        raise OptionError(f"switches: expected a string such as 'pq30a0.1', got {opts!r}")
    return opts


class Result:
    """One triangulation: ``mesh`` (the triangle package's output dict), and
    the statistics, quality statistics and exact check of the run."""

    def __init__(self, run, mesh):
        self._run = run
        self.mesh = mesh

    def statistics(self):
        """The run's timings and counts, as ``clmesh --stats-json`` writes them."""
        return json.loads(self._run.statistics_json())

    def quality_statistics(self):
        """Triangle's -V mesh quality statistics (angles, areas, aspect ratios)."""
        return self._run.quality_statistics()

    def check(self):
        """The problems the exact check (-C) finds; an empty list for a valid mesh."""
        return list(self._run.check())


def _unsuitable(function):
    if function is not None and not callable(function):
        raise OptionError("unsuitable: expected a function f(a, b, c, area) -> bool, "
                          f"got {function!r}")
    return function


def _input(tri, switches):
    """The compiled Input of a triangle-style dict."""
    return _clmesh.input(**_arrays(tri), switches=switches)


def _result(core, tri):
    """The Result of a compiled Run of the dict `tri`; with -C, CheckError
    when the exact check fails."""
    result = Result(core, _mesh_dict(core, tri))
    if core.options["check"]:
        problems = result.check()
        if problems:
            raise CheckError("the mesh fails the exact check: " + "; ".join(problems))
    return result


def run(tri, opts="", device=None, *, size_field=None, unsuitable=None):
    """triangulate() that also keeps what the run counted: a Result."""
    switches = _switches(opts)
    given = _input(tri, switches)
    field = None if size_field is None else _size_field(size_field)
    core = _clmesh.triangulate(given, switches=switches, device=_device_spec(device),
                               size_field=field, unsuitable=_unsuitable(unsuitable))
    return _result(core, tri)


def triangulate(tri, opts="", device=None, *, size_field=None, unsuitable=None):
    """The mesh of `tri` (a dict with vertices, and optionally vertex_markers,
    vertex_attributes, segments, segment_markers, holes, regions; with -r the
    mesh to refine: triangles, triangle_attributes, and with -a alone
    triangle_max_area) with Triangle's switches `opts`, as a dict of NumPy
    arrays as the triangle package returns it. Raises InputError,
    OptionError, DeviceError.

    Size control beyond -a, each refining alone or with -q and -a (a
    triangle is refined when any bound asks): `size_field`, a background
    mesh dict with vertices (N, 2), triangles (M, 3, counter-clockwise) and
    area (N), the largest area wanted at each vertex, interpolated linearly
    and met at every triangle's centroid; `unsuitable`, a function
    f(a, b, c, area) -> bool (Triangle's triunsuitable), called with the
    corners of every triangle refinement creates as (x, y) tuples and its
    area, true to refine it. What f raises reaches the caller unchanged."""
    return run(tri, opts, device, size_field=size_field, unsuitable=unsuitable).mesh


def _failed(error, index):
    """`error` as the error of input `index` of a batch: with an `index`
    attribute, and clmesh's errors with "input <index>: " before the message
    (what an unsuitable function raised stays the same object)."""
    if isinstance(error, Error):
        error = type(error)(f"input {index}: {error}")
    error.index = index
    return error


def triangulate_many(inputs, opts="", device=None, *, size_field=None, unsuitable=None,
                     errors="raise", streams=None):
    """The meshes of many dicts with the same switches, field and function:
    the list of what triangulate() returns for each, in order, meshed through
    the library's batch (the device set up once, the GIL released once).

    Every dict is checked before anything is meshed. errors="raise" (the
    default) raises the first failing input's error, as a loop of
    triangulate() would, and meshes no input after it: a dict that cannot be
    converted raises before any meshing. errors="return" meshes every input
    and puts the exception object in place of a failed input's dict. clmesh's
    errors name the input ("input 3: ..."), and every error has the input's
    position as its `index`; what `unsuitable` raises is the same object (a
    KeyboardInterrupt or other BaseException that is no Exception ends the
    batch at once, in both modes). Switches that are invalid, or a device
    that cannot be opened, raise OptionError or DeviceError for the batch.

    streams: how many inputs are meshed at once, each on a thread and a
    command queue of its own (None: several on a GPU, one elsewhere). The
    meshes are the same whatever it is; with `unsuitable` it is one, and
    PoCL's in-thread device takes one whatever it says."""
    if errors not in ("raise", "return"):
        raise OptionError(f"errors: expected 'raise' or 'return', got {errors!r}")
    if streams is not None and (isinstance(streams, bool) or not isinstance(streams, int)
                                or streams < 1):
        raise OptionError(f"streams: expected a positive integer or None, got {streams!r}")
    if isinstance(inputs, dict):
        raise InputError("triangulate_many: expected a list of dicts, got a dict "
                         "(triangulate() meshes one)")
    tris = list(inputs)
    switches = _switches(opts)
    _clmesh.parse_switches(switches)  # OptionError before the inputs' errors
    field = None if size_field is None else _size_field(size_field)
    unsuitable = _unsuitable(unsuitable)
    meshes = [None] * len(tris)
    meshed = []  # the positions of the inputs converted, in order
    converted = []
    for index, tri in enumerate(tris):
        try:
            converted.append(_input(tri, switches))
            meshed.append(index)
        except Error as error:
            failure = _failed(error, index)
            if errors == "raise":
                raise failure from None
            meshes[index] = failure
    outcomes = _clmesh.triangulate_many(converted, switches=switches,
                                        device=_device_spec(device), size_field=field,
                                        unsuitable=unsuitable, stop_at_error=errors == "raise",
                                        streams=streams or 0)
    for index, outcome in zip(meshed, outcomes):
        if isinstance(outcome, BaseException):
            if not isinstance(outcome, Exception):
                raise outcome
            meshes[index] = _failed(outcome, index)
        else:
            try:
                meshes[index] = _result(outcome, tris[index]).mesh
            except CheckError as error:
                meshes[index] = _failed(error, index)
        if errors == "raise" and isinstance(meshes[index], Exception):
            raise meshes[index]
    return meshes


def delaunay(pts, device=None):
    """The Delaunay triangles of the points (int32, (M, 3))."""
    return triangulate({"vertices": pts}, "", device)["triangles"]


def convex_hull(pts, device=None):
    """The convex hull's edges (int32, (H, 2)), clockwise as in the triangle package."""
    return triangulate({"vertices": pts}, "c", device)["segments"]


def voronoi(pts, device=None):
    """The Voronoi diagram of the points, as the triangle package returns it:
    ``points, edges, ray_origin, ray_direct``. points (float64, (V, 2)) are
    the circumcentres of the Delaunay triangles, numbered as delaunay()'s
    triangles; edges (int32, (E, 2)) join two of them; each ray starts at
    points[ray_origin[i]] (int32, (R,)) and runs along ray_direct[i]
    (float64, (R, 2)): the hull edge it crosses turned a quarter clockwise,
    outwards, as long as that edge."""
    core = _clmesh.triangulate(_input({"vertices": pts}, "v"), switches="v",
                               device=_device_spec(device))
    ends, directions = core.voronoi_edges()
    ray = ends[:, 1] < 0
    return core.voronoi_points(), ends[~ray], ends[ray, 0], directions[ray]


def statistics(result):
    """The timings and counts of a Result from run(), as --stats-json writes them."""
    return result.statistics()


def quality_statistics(mesh):
    """Triangle's -V quality statistics of a Result, or of any dict with
    vertices and triangles (another mesher's too)."""
    if isinstance(mesh, Result):
        return mesh.quality_statistics()
    from ._input import floats, integers
    vertices = floats(mesh, "vertices", 2)
    if vertices is None or mesh.get("triangles") is None:
        raise InputError("quality_statistics: expected a dict with 'vertices' and 'triangles'")
    return _clmesh.quality_statistics(vertices, integers(mesh, "triangles", 3,
                                                         limit=vertices.shape[0]))


def check_mesh(result):
    """The problems the exact check (-C) finds in a Result's mesh; empty when valid."""
    return result.check()
