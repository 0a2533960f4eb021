"""The triangle package's input dictionary as the arrays clmesh._clmesh takes.

Everything Python can get wrong is refused here with an InputError naming the
key, before the library sees it: shapes, dtypes, non-finite coordinates,
indices out of range, integers that do not fit.
"""

import numpy as np

from ._errors import InputError

INT32 = np.iinfo(np.int32)

# Keys the triangle package reads (and ignores unless its switches use them),
# or returns and so may come back in a dictionary passed on again.
KNOWN_KEYS = {
    "vertices", "vertex_markers", "vertex_attributes", "segments", "segment_markers",
    "holes", "regions", "triangles", "triangle_attributes", "triangle_max_area",
    "neighbors", "edges", "edge_markers",
}


def _numeric(value, key):
    try:
        array = np.asarray(value)
    except (ValueError, TypeError) as error:
        raise InputError(f"{key}: not an array ({error})") from None
    if array.dtype.kind not in "biuf":
        raise InputError(f"{key}: expected numbers, got an array of dtype {array.dtype}")
    return array


def _shaped(array, key, columns, rows=None):
    """array as (rows, columns): one column may come as a flat array, and an
    empty list stands for no rows."""
    if array.size == 0 and array.ndim <= 1 and columns is not None:
        array = array.reshape(0, columns)
    if array.ndim == 1 and columns in (1, None):
        array = array.reshape(-1, 1)
    if array.ndim != 2 or (columns is not None and array.shape[1] != columns):
        want = f"(N, {columns})" if columns is not None else "(N, K)"
        raise InputError(f"{key}: expected shape {want}, got {array.shape}")
    if rows is not None and array.shape[0] != rows:
        raise InputError(f"{key}: {array.shape[0]} rows, expected {rows} "
                         "(one per vertex, segment or triangle)")
    return array


def floats(tri, key, columns, rows=None, finite=True):
    """A float64 (N, columns) C-contiguous array from tri[key] (None: absent)."""
    if tri.get(key) is None:
        return None
    array = _shaped(_numeric(tri[key], key), key, columns, rows).astype(np.float64)
    if finite and not np.isfinite(array).all():
        bad = int(np.argwhere(~np.isfinite(array))[0][0])
        raise InputError(f"{key}: row {bad} is not finite ({array[bad].tolist()})")
    return np.ascontiguousarray(array)


def integers(tri, key, columns, rows=None, limit=None):
    """An int32 (N, columns) C-contiguous array from tri[key] (None: absent);
    with limit, every value must lie in [0, limit)."""
    if tri.get(key) is None:
        return None
    array = _shaped(_numeric(tri[key], key), key, columns, rows)
    if array.dtype.kind == "f":
        if not (np.isfinite(array).all() and (array == np.round(array)).all()):
            raise InputError(f"{key}: expected integers")
    low, high = (0, limit - 1) if limit is not None else (INT32.min, INT32.max)
    if array.size and (array.min() < low or array.max() > high):
        bad = int(np.argwhere((array < low) | (array > high))[0][0])
        what = (f"index out of range (0 to {limit - 1})" if limit is not None
                else "out of int32 range")
        raise InputError(f"{key}: row {bad} ({array[bad].tolist()}): {what}")
    return np.ascontiguousarray(array.astype(np.int32))


def arrays(tri):
    """The arrays of clmesh._clmesh.triangulate() from a triangle-style dict."""
    if not isinstance(tri, dict):
        raise InputError(f"expected a dict with 'vertices', got {type(tri).__name__}")
    unknown = sorted(str(key) for key in tri if key not in KNOWN_KEYS)
    if unknown:
        raise InputError(f"unknown key {unknown[0]!r}; known: {', '.join(sorted(KNOWN_KEYS))}")
    vertices = floats(tri, "vertices", 2)
    if vertices is None:
        raise InputError("'vertices' is missing")
    n = vertices.shape[0]
    if n < 3:
        raise InputError(f"input must have at least three vertices, found {n}")
    segments = integers(tri, "segments", 2, limit=n)
    m = 0 if segments is None else segments.shape[0]
    none_int = np.zeros((0, 1), np.int32)
    attributes = floats(tri, "vertex_attributes", None, rows=n, finite=False)
    regions = floats(tri, "regions", 4)
    # -r: the mesh to refine (the library takes it only with -r, as Triangle).
    triangles = integers(tri, "triangles", 3, limit=n)
    t = 0 if triangles is None else triangles.shape[0]
    # Maximum areas <= 0 (or infinite) mean none; the library refuses NaN.
    max_areas = floats(tri, "triangle_max_area", 1, rows=t, finite=False)
    return dict(
        vertices=vertices,
        vertex_markers=_or(integers(tri, "vertex_markers", 1, rows=n), none_int),
        vertex_attributes=_or(attributes, np.zeros((n, 0))),
        segments=_or(segments, np.zeros((0, 2), np.int32)),
        segment_markers=_or(integers(tri, "segment_markers", 1, rows=m), none_int),
        holes=_or(floats(tri, "holes", 2), np.zeros((0, 2))),
        regions=_or(regions, np.zeros((0, 4))),
        triangles=_or(triangles, np.zeros((0, 3), np.int32)),
        has_triangles=triangles is not None,
        triangle_attributes=_or(floats(tri, "triangle_attributes", None, rows=t),
                                np.zeros((t, 0))),
        triangle_max_area=_or(max_areas, np.zeros((0, 1))),
        has_triangle_max_area=max_areas is not None,
    )


def _or(array, empty):
    return empty if array is None else array

