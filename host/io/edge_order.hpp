// clmesh — the order in which Triangle lists a mesh's edges (.edge, .v.edge,
// the -o2 middle nodes): by triangle, then edge; an interior edge by the
// triangle with the smaller index.
#pragma once

#include "clmesh/geometry.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace clmesh {

// Calls visit(t, i, other) for every edge once, in that order: edge i of
// triangle t lies opposite triangles[t][i], from vertex i + 1 to vertex i + 2
// (counter-clockwise, the triangle on its left); other is the triangle across
// it, -1 on the boundary.
template <typename Visit>
void visit_edges(const std::vector<Triangle> &triangles,
                 const std::vector<std::array<int32_t, 3>> &neighbors, Visit visit) {
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int i = 0; i < 3; ++i) {
      const int32_t other = neighbors[t][i];
      if (other == -1 || static_cast<int64_t>(t) < other)
        visit(t, i, other);
    }
}

} // namespace clmesh
