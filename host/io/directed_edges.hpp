// clmesh — the directed edges of a set of triangles, grouped by their first
// vertex: each triangle's three edges a -> b counter-clockwise, and for each
// vertex a its edges in increasing b, then increasing triangle. Grouped by a
// counting sort, each vertex's few edges then sorted, so a given mesh's
// million triangles are checked and turned into constraints quickly (-r).
#pragma once

#include "clmesh/geometry.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace clmesh {

class DirectedEdges {
public:
  struct Edge {
    int32_t head;           // b of a -> b
    uint32_t triangle : 30; // the triangle it bounds (on its left)
    uint32_t corner : 2;    // a's corner in that triangle (b is the next one)
  };

  // How many edges ahead a loop over the edges in random order of memory
  // (reverses()) prefetches what a later edge reads.
  static constexpr std::size_t kPrefetchAhead = 8;

  // Every corner must lie in [0, vertices).
  DirectedEdges(const std::vector<Triangle> &triangles, std::size_t vertices);

  std::size_t vertices() const { return first_.size() - 1; }
  // Vertex a's edges: edges()[first(a) .. first(a + 1)).
  std::size_t first(std::size_t a) const { return first_[a]; }
  const std::vector<Edge> &edges() const { return edges_; }
  // Is there an edge a -> b?
  bool has(int32_t a, int32_t b) const;
  // The first triangle with the edge a -> b, or -1.
  int64_t triangle_of(int32_t a, int32_t b) const;
  // For every edge a -> b (its index in edges()), the index of the first
  // edge b -> a, or -1: the edge's other side. One search per pair of
  // vertices, in place of one per edge (has, triangle_of).
  std::vector<int64_t> reverses() const;

private:
  std::vector<std::size_t> first_; // vertices + 1 offsets
  std::vector<Edge> edges_;
};

} // namespace clmesh
