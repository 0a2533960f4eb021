// clmesh — Phase 2 of GPU-DT: triangulation construction from the digital
// Voronoi diagram (thesis §4.1.2, Phase 2; [QCT12]).
//
// A digital Voronoi vertex is a 2x2 block of pixels coloured by three or four
// distinct sites: its sites, read counter-clockwise around the block, make one
// triangle (three sites) or two (four sites, split along the diagonal the
// exact in-circle test prefers). The texture border, walked counter-clockwise,
// gives the outer cycle of sites; each of its edges gets a ghost triangle with
// the vertex at infinity, so the construction is closed like the rest of the
// mesh. Neighbour links follow the Voronoi edges from block to block. Slots
// come from prefix sums, so the result does not depend on the work-group size
// or the order of work-items. Whatever does not fit together (a link that is
// not returned, a site met twice on the border) flags its sites: Phase 3
// leaves them out of the diagram and the construction is repeated.
#include "common.h"

// The site colours of block b's corners, counter-clockwise from its
// lower-left pixel.
static inline void load_corners(__global const int *voronoi, int grid, int b, int *c) {
  const int side = grid - 1, x = b % side, y = b / side;
  c[0] = voronoi[y * grid + x];
  c[1] = voronoi[y * grid + x + 1];
  c[2] = voronoi[(y + 1) * grid + x + 1];
  c[3] = voronoi[(y + 1) * grid + x];
}

// The distinct sites of block b counter-clockwise from its lower-left pixel,
// consecutive repeats removed; returns how many triangles they make.
static inline int block_sites(__global const int *voronoi, int grid, int b, int *s) {
  int c[4];
  load_corners(voronoi, grid, b, c);
  int k = 0;
  for (int i = 0; i < 4; ++i)
    if (c[i] != c[(i + 3) & 3])
      s[k++] = c[i];
  if (k == 3)
    return 1;
  if (k == 4 && s[0] != s[2] && s[1] != s[3])
    return 2;
  return 0; // inside a region, on a Voronoi edge, or a site met at two corners
}

__kernel void count_block_triangles(__global const int *voronoi, __global int *counts,
                                    const int grid) {
  const int b = get_global_id(0), side = grid - 1;
  if (b >= side * side)
    return;
  int s[4];
  counts[b] = block_sites(voronoi, grid, b, s);
}

__kernel void emit_block_triangles(__global const double2 *points, __global const int *voronoi,
                                   __global const int *offsets, __global int *tri_vertex,
                                   __global int *block_of, const int grid) {
  const int b = get_global_id(0), side = grid - 1;
  if (b >= side * side)
    return;
  int s[4];
  const int count = block_sites(voronoi, grid, b, s);
  if (count == 0)
    return;
  int first = 0; // the diagonal from s[first] to s[first + 2]
  if (count == 2) {
    const double2 a = points[s[0]], p = points[s[1]], c = points[s[2]], d = points[s[3]];
    if (clm_orient2d(a.x, a.y, p.x, p.y, c.x, c.y) > 0 &&
        clm_incircle_sos(a.x, a.y, p.x, p.y, c.x, c.y, d.x, d.y) > 0)
      first = 1;
  }
  const int t = offsets[b];
  for (int k = 0; k < count; ++k) {
    block_of[t + k] = b;
    tri_vertex[3 * (t + k)] = s[first];
    tri_vertex[3 * (t + k) + 1] = s[(first + k + 1) & 3];
    tri_vertex[3 * (t + k) + 2] = s[(first + k + 2) & 3];
  }
}

// Site of border position i, counter-clockwise from the lower-left pixel, and
// whether it differs from the previous position's (a new site of the cycle).
__kernel void border_sites(__global const int *voronoi, __global int *site, __global int *starts,
                           const int grid) {
  const int i = get_global_id(0), side = grid - 1, length = 4 * side;
  if (i >= length)
    return;
  int positions[2];
  for (int k = 0; k < 2; ++k) {
    const int j = k == 0 ? i : (i + length - 1) % length, run = j % side;
    const int x = j < side ? run : (j < 2 * side ? side : (j < 3 * side ? side - run : 0));
    const int y = j < side ? 0 : (j < 2 * side ? run : (j < 3 * side ? side : side - run));
    positions[k] = voronoi[y * grid + x];
  }
  site[i] = positions[0];
  starts[i] = positions[0] != positions[1];
}

// Ghost triangle g on the border edge cycle[g] -> cycle[g + 1], stored after
// the `first` real slots as (cycle[g + 1], cycle[g], infinite); its real edge
// is linked by link_block_triangles.
__kernel void emit_ghosts(__global const int *cycle, __global int *tri_vertex,
                          __global int *tri_neighbor, const int first, const int m) {
  const int g = get_global_id(0);
  if (g >= m)
    return;
  const int t = first + g;
  const int previous = first + (g + m - 1) % m, next = first + (g + 1) % m;
  store_triangle(tri_vertex, tri_neighbor, t, cycle[(g + 1) % m], cycle[g], CLM_INFINITE,
                 encode_link(previous, 1), encode_link(next, 0), INT_MAX);
}

// How often each site appears on the border cycle.
__kernel void count_border_visits(__global const int *cycle, volatile __global int *visits,
                                  const int m) {
  const int g = get_global_id(0);
  if (g < m)
    atomic_inc(&visits[cycle[g]]);
}

// A site met twice on the border would pinch the mesh.
__kernel void flag_repeated_border_sites(__global const int *cycle, __global const int *visits,
                                         __global int *bad, const int m) {
  const int g = get_global_id(0);
  if (g < m && visits[cycle[g]] > 1)
    bad[cycle[g]] = 1;
}

// Neighbour links follow the digital Voronoi edges. The edge u -> v of a
// triangle is where the corner colours of its block change from u to v,
// counter-clockwise; the boundary between regions u and v leaves the block
// through that side. It is followed block by block (a block of two colours
// passes it on through its other side) to the next Voronoi vertex block, whose
// triangle holds v -> u, or out of the texture to the ghost of that border
// edge. Blocks are numbered y * (grid - 1) + x; side k of a block joins its
// corners k and k + 1 (0 bottom, 1 right, 2 top, 3 left).

// The link of the directed edge from -> to among the triangles of block b, or -1.
static inline int block_edge(__global const int *tri_vertex, __global const int *offsets, int b,
                             int blocks, int real, int from, int to) {
  const int end = b + 1 < blocks ? offsets[b + 1] : real;
  for (int t = offsets[b]; t < end; ++t)
    for (int i = 0; i < 3; ++i)
      if (tri_vertex[3 * t + next3(i)] == from && tri_vertex[3 * t + prev3(i)] == to)
        return encode_link(t, i);
  return -1;
}

// Border position (counter-clockwise from the lower-left pixel) of the second
// pixel of side k of a block on the texture's edge.
static inline int border_position(int grid, int x, int y, int k) {
  const int side = grid - 1;
  return k == 0 ? x + 1
                : (k == 1 ? side + y + 1 : (k == 2 ? 3 * side - x : (4 * side - y) % (4 * side)));
}

// Several triangles reaching one ghost (no triangulation) leave it the
// smallest link; check_links flags the others.
__kernel void link_block_triangles(__global const int *voronoi, __global const int *offsets,
                                   __global const int *block_of, __global const int *tri_vertex,
                                   volatile __global int *tri_neighbor,
                                   __global const int *border_offsets, const int first_ghost,
                                   const int ghosts, const int real, const int grid) {
  const int t = get_global_id(0);
  if (t >= real)
    return;
  const int side = grid - 1, blocks = side * side, block = block_of[t];
  int c[4];
  load_corners(voronoi, grid, block, c);
  for (int i = 0; i < 3; ++i) {
    const int from = tri_vertex[3 * t + next3(i)], to = tri_vertex[3 * t + prev3(i)];
    // The side where the corner colours change from -> to; none: the diagonal
    // of a four-site block, shared with the block's other triangle.
    int k = -1;
    for (int j = 0; j < 4; ++j)
      if (c[j] == from && c[(j + 1) & 3] == to)
        k = j;
    int link = -1;
    if (k < 0)
      link = block_edge(tri_vertex, offsets, block, blocks, real, to, from);
    int b = block;
    for (int step = 0; k >= 0 && step < 4 * grid; ++step) {
      const int x = b % side, y = b / side;
      const int nx = x + (k == 1) - (k == 3), ny = y + (k == 2) - (k == 0);
      if (nx < 0 || ny < 0 || nx >= side || ny >= side) { // out of the texture: a ghost
        const int g = (border_offsets[border_position(grid, x, y, k)] + ghosts - 1) % ghosts;
        link = encode_link(first_ghost + g, 2);
        atomic_min(&tri_neighbor[3 * (first_ghost + g) + 2], encode_link(t, i));
        break;
      }
      b = ny * side + nx;
      k = (k + 2) & 3; // the same side seen from the next block: to -> from
      int d[4];
      load_corners(voronoi, grid, b, d);
      int changes = 0, exit = -1;
      for (int j = 0; j < 4; ++j)
        if (d[j] != d[(j + 1) & 3]) {
          ++changes;
          if (j != k)
            exit = j;
        }
      if (changes == 4 && (d[0] == d[2] || d[1] == d[3])) {
        // A pinched block (x y x z): x counts as connected through it, so
        // the boundary turns around the lone corner of the side it came in by.
        const int lone = (d[0] == d[2]) == ((k & 1) == 0) ? (k + 1) & 3 : k;
        exit = lone == k ? (k + 3) & 3 : lone;
      } else if (changes != 2) { // a Voronoi vertex block: its triangle holding to -> from
        link = block_edge(tri_vertex, offsets, b, blocks, real, to, from);
        break;
      }
      k = exit; // the boundary leaves through this side
    }
    tri_neighbor[3 * t + i] = link;
  }
}

// A link that is missing or not returned, or whose edge is not this edge
// reversed, flags the sites of the edge.
__kernel void check_links(__global const int *tri_vertex, __global const int *tri_neighbor,
                          __global int *bad, const int slots) {
  const int t = get_global_id(0);
  if (t >= slots)
    return;
  for (int i = 0; i < 3; ++i) {
    const int a = tri_vertex[3 * t + next3(i)], b = tri_vertex[3 * t + prev3(i)];
    const int link = tri_neighbor[3 * t + i];
    bool good = link >= 0 && link_triangle(link) < slots;
    if (good) {
      const int u = link_triangle(link), j = link_edge(link);
      good = j < 3 && tri_neighbor[3 * u + j] == encode_link(t, i) &&
             tri_vertex[3 * u + next3(j)] == b && tri_vertex[3 * u + prev3(j)] == a;
    }
    if (!good) {
      if (a >= 0)
        bad[a] = 1;
      if (b >= 0)
        bad[b] = 1;
    }
  }
}
