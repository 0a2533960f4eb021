"""A sizing field's dictionary as the checked field of clmesh._clmesh.

triangulate(size_field=...) takes a background mesh in the triangle package's
style: 'vertices' (N, 2), 'triangles' (M, 3), counter-clockwise and
zero-based, and 'area' (N or (N, 1)), the largest triangle area wanted at
each vertex. Other keys of a mesh dict (markers, segments...) are ignored, so
that a mesh clmesh returned serves with an 'area' added. Shapes, dtypes,
non-finite values and indices are refused here, naming the key; the library
refuses the rest (areas not positive, triangles not counter-clockwise).
"""

from . import _clmesh
from ._errors import InputError
from ._input import KNOWN_KEYS, floats, integers

REQUIRED_KEYS = ("vertices", "triangles", "area")


def size_field(field):
    """The clmesh._clmesh.SizeField of a dict with vertices, triangles and area."""
    if not isinstance(field, dict):
        raise InputError("size_field: expected a dict with 'vertices', 'triangles' and 'area', "
                         f"got {type(field).__name__}")
    unknown = sorted(str(key) for key in field if key not in KNOWN_KEYS and key != "area")
    if unknown:
        raise InputError(f"size_field: unknown key {unknown[0]!r}; "
                         f"expected {', '.join(REQUIRED_KEYS)} (and a mesh dict's keys)")
    missing = [key for key in REQUIRED_KEYS if field.get(key) is None]
    if missing:
        raise InputError(f"size_field: {missing[0]!r} is missing")
    try:
        vertices = floats(field, "vertices", 2)
        n = vertices.shape[0]
        area = floats(field, "area", 1, rows=n)
        triangles = integers(field, "triangles", 3, limit=n)
    except InputError as error:
        raise InputError(f"size_field: {error}") from None
    return _clmesh.size_field(vertices, area, triangles)
