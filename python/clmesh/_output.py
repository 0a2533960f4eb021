"""A clmesh._clmesh.Run as the triangle package's output dictionary.

The keys, dtypes and shapes follow the triangle package: vertices (float64,
(N, 2)), vertex_markers and the other markers (int32, (N, 1)), index arrays
int32 and zero-based; which keys appear depends on the switches as there
(-N, -E, -B, -n, -e, -p, -c, -A, -o2), in its order, and empty arrays are
left out. With -o2 the triangles have six columns (corners, then the middles
of the edges opposite them), and the middle nodes are numbered after the
vertices, their coordinates, attributes and markers appended to those arrays.
"""

import numpy as np


def hull_segments(triangles, neighbors):
    """-c without -p: the boundary edges of the triangulation, clockwise as
    Triangle writes them, with marker 1."""
    t, i = np.nonzero(neighbors < 0)
    segments = np.stack([triangles[t, (i + 2) % 3], triangles[t, (i + 1) % 3]], axis=1)
    return segments.astype(np.int32), np.ones((len(t), 1), np.int32)


def mesh_dict(run, given):
    """The output dict of `run`; `given` is the input dict (holes and regions
    are handed back with -p, as the triangle package does)."""
    options = run.options
    markers = not options["no_boundary_markers"]
    numbers = run.vertex_numbers().ravel() if options["jettison"] else None

    def renumbered(indices):
        return indices if numbers is None else numbers[indices]

    # -o2: the middle nodes follow the vertices (those written, with -j).
    second_order = options["second_order"]
    written = len(run.points()) if numbers is None else int((numbers >= 0).sum())

    def with_midpoints(values, midpoints):
        return np.concatenate([values, midpoints()]) if second_order else values

    out = {}
    if not options["no_node_file"]:
        keep = slice(None) if numbers is None else numbers >= 0
        out["vertices"] = with_midpoints(run.points()[keep], run.edge_midpoints)
        attributes = run.point_attributes()
        if attributes.shape[1]:
            out["vertex_attributes"] = with_midpoints(attributes[keep],
                                                      run.edge_midpoint_attributes)
        if markers:
            out["vertex_markers"] = with_midpoints(run.point_markers()[keep],
                                                   run.edge_midpoint_markers)
    triangles = run.triangles()
    if not options["no_ele_file"]:
        out["triangles"] = renumbered(triangles)
        if second_order:
            middles = (written + run.triangle_midpoints()).astype(np.int32)
            out["triangles"] = np.concatenate([out["triangles"], middles], axis=1)
        attributes = run.triangle_attributes()
        if attributes.shape[1]:
            out["triangle_attributes"] = attributes
    if options["neighbors"] and not options["no_ele_file"]:
        out["neighbors"] = run.neighbors()
    if options["pslg"] or options["convex_hull"]:
        if options["pslg"]:
            segments, segment_markers = run.segments()
        else:
            segments, segment_markers = hull_segments(triangles, run.neighbors())
        out["segments"] = renumbered(segments)
        if markers:
            out["segment_markers"] = segment_markers
    if options["pslg"]:
        for key in ("holes", "regions"):
            if given.get(key) is not None:
                columns = 2 if key == "holes" else 4
                out[key] = np.asarray(given[key], dtype=np.float64).reshape(-1, columns)
    if options["edges"]:
        edges, edge_markers = run.edges()
        out["edges"] = renumbered(edges)
        if markers:
            out["edge_markers"] = edge_markers
    return {key: value for key, value in out.items() if len(value)}
