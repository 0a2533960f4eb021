// clmesh — the resident mesh's buffers (thesis §2.2 data structure, and the
// per-point state of refinement, §3.3.2) as one list of kernel parameters.
//
// A kernel cannot take a struct of pointers (OpenCL 1.2), so a kernel that
// works on the mesh declares CLM_TRIANGULATION_PARAMS (Delaunay and
// constrained phases) or CLM_MESH_PARAMS (refinement: the same list and the
// per-point state after it) first among its parameters and passes
// CLM_TRIANGULATION_ARGS or CLM_MESH_ARGS on to helper functions that declare
// the same. The host sets them with DeviceMesh::bind_triangulation or
// DeviceMesh::bind, in this order, so the order is written down once on each
// side.
#ifndef CLMESH_MESH_PARAMS_H
#define CLMESH_MESH_PARAMS_H

// points: coordinates; tri_vertex, tri_neighbor: 3 per triangle (common.h);
// tri_mark: atomic-minimum marks; modified_stamp and children: the step that
// last rewrote a slot and the slots that replaced it; vertex_triangle: one
// triangle per vertex; constraint_start, constraint_adjacent, constrained:
// the constraints as rows per vertex, and whether there are any;
// original_id: input number of a point; duplicate_of: -1 or the point a
// duplicate stands for; location, location_edge: where a point waiting for
// insertion lies; tri_region, regional: with regions (a PSLG refined with
// regional area bounds or attributes), the region of each triangle slot
// (-1: none), kept by every step that rewrites triangles (a flip never
// crosses a segment, so it leaves both slots in their region), and whether
// it is in use (else tri_region has one entry). Every one of them exists
// from upload on.
#define CLM_TRIANGULATION_PARAMS                                                                   \
  __global double2 *points, __global int *tri_vertex, __global int *tri_neighbor,                  \
      volatile __global uint *tri_mark, __global int *modified_stamp, __global int *children,      \
      __global int *vertex_triangle, __global const int *constraint_start,                         \
      __global const int *constraint_adjacent, const int constrained, __global int *original_id,   \
      __global int *duplicate_of, __global int *location, __global int *location_edge,             \
      __global int *tri_region, const int regional

#define CLM_TRIANGULATION_ARGS                                                                     \
  points, tri_vertex, tri_neighbor, tri_mark, modified_stamp, children, vertex_triangle,           \
      constraint_start, constraint_adjacent, constrained, original_id, duplicate_of, location,     \
      location_edge, tri_region, regional

// Refinement adds per point: point_state (refinement.h), insertion_radius2,
// point_priority, point_segment (refinement.h); and the segments:
// segment_end (2 per segment) and constraint_segment (per entry of
// constraint_adjacent: its segment). Allocated by
// DeviceMesh::enable_refinement.
#define CLM_MESH_PARAMS                                                                            \
  CLM_TRIANGULATION_PARAMS, __global int *point_state, __global double *insertion_radius2,         \
      __global uint *point_priority, __global int *point_segment, __global const int *segment_end, \
      __global int *constraint_segment

#define CLM_MESH_ARGS                                                                              \
  CLM_TRIANGULATION_ARGS, point_state, insertion_radius2, point_priority, point_segment,           \
      segment_end, constraint_segment

#endif
