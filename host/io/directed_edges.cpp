// clmesh — the directed edges of a set of triangles (directed_edges.hpp).
#include "io/directed_edges.hpp"

#include "clmesh/errors.hpp"

#include <algorithm>
#include <limits>
#include <numeric>

namespace clmesh {

DirectedEdges::DirectedEdges(const std::vector<Triangle> &triangles, std::size_t vertices)
    : first_(vertices + 1, 0), edges_(3 * triangles.size()) {
  if (triangles.size() > std::numeric_limits<uint32_t>::max())
    throw InputError("input", 0, "more than 2^32 triangles");
  for (const Triangle &t : triangles)
    for (const int32_t corner : t)
      ++first_[static_cast<std::size_t>(corner) + 1];
  std::partial_sum(first_.begin(), first_.end(), first_.begin());
  std::vector<std::size_t> next(first_.begin(), first_.end() - 1);
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      edges_[next[static_cast<std::size_t>(triangles[t][k])]++] = {triangles[t][(k + 1) % 3],
                                                                   static_cast<uint32_t>(t)};
  const auto order = [](const Edge &p, const Edge &q) {
    return p.head != q.head ? p.head < q.head : p.triangle < q.triangle;
  };
  for (std::size_t a = 0; a < vertices; ++a)
    std::sort(edges_.begin() + static_cast<std::ptrdiff_t>(first_[a]),
              edges_.begin() + static_cast<std::ptrdiff_t>(first_[a + 1]), order);
}

bool DirectedEdges::has(int32_t a, int32_t b) const { return triangle_of(a, b) >= 0; }

int64_t DirectedEdges::triangle_of(int32_t a, int32_t b) const {
  const auto from = edges_.begin() + static_cast<std::ptrdiff_t>(first_[a]),
             to = edges_.begin() + static_cast<std::ptrdiff_t>(first_[a + 1]);
  const auto at =
      std::lower_bound(from, to, b, [](const Edge &e, int32_t head) { return e.head < head; });
  return at != to && at->head == b ? static_cast<int64_t>(at->triangle) : -1;
}

} // namespace clmesh
