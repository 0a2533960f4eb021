// clmesh — the directed edges of a set of triangles (directed_edges.hpp).
#include "io/directed_edges.hpp"

#include "clmesh/errors.hpp"
#include "runtime/host_threads.hpp"

#include <algorithm>
#include <limits>
#include <numeric>

namespace clmesh {

DirectedEdges::DirectedEdges(const std::vector<Triangle> &triangles, std::size_t vertices)
    : first_(vertices + 1, 0), edges_(3 * triangles.size()) {
  if (triangles.size() >= std::size_t{1} << 30)
    throw InputError("input", 0, "2^30 triangles or more");
  for (const Triangle &t : triangles)
    for (const int32_t corner : t)
      ++first_[static_cast<std::size_t>(corner) + 1];
  std::partial_sum(first_.begin(), first_.end(), first_.begin());
  // The parts take the vertices apart: each reads every triangle, places the
  // edges from its own vertices and sorts those.
  run_parts(host_threads(edges_.size()), [&](int part, int parts) {
    const auto [first, end] = part_range(vertices, part, parts);
    const auto low = static_cast<int32_t>(first), high = static_cast<int32_t>(end);
    std::vector<std::size_t> next(first_.begin() + low, first_.begin() + high);
    for (std::size_t t = 0; t < triangles.size(); ++t)
      for (int k = 0; k < 3; ++k) {
        const int32_t a = triangles[t][k];
        if (a >= low && a < high)
          edges_[next[static_cast<std::size_t>(a - low)]++] = {
              triangles[t][(k + 1) % 3], static_cast<uint32_t>(t), static_cast<uint32_t>(k)};
      }
    const auto order = [](const Edge &p, const Edge &q) {
      return p.head != q.head ? p.head < q.head : p.triangle < q.triangle;
    };
    for (auto a = static_cast<std::size_t>(low); a < static_cast<std::size_t>(high); ++a)
      std::sort(edges_.begin() + static_cast<std::ptrdiff_t>(first_[a]),
                edges_.begin() + static_cast<std::ptrdiff_t>(first_[a + 1]), order);
  });
}

bool DirectedEdges::has(int32_t a, int32_t b) const { return triangle_of(a, b) >= 0; }

int64_t DirectedEdges::triangle_of(int32_t a, int32_t b) const {
  const auto from = edges_.begin() + static_cast<std::ptrdiff_t>(first_[a]),
             to = edges_.begin() + static_cast<std::ptrdiff_t>(first_[a + 1]);
  const auto at =
      std::lower_bound(from, to, b, [](const Edge &e, int32_t head) { return e.head < head; });
  return at != to && at->head == b ? static_cast<int64_t>(at->triangle) : -1;
}

std::vector<int64_t> DirectedEdges::reverses() const {
  std::vector<int64_t> reverse(edges_.size(), -1);
  const auto by_head = [](const Edge &e, int32_t head) { return e.head < head; };
  // Each pair of vertices a < b once, from a's first edge a -> b: its reverse
  // is b's first edge b -> a, and every edge b -> a has that first a -> b as
  // its reverse. The pair's entries are written from a's part alone, so the
  // parts (of the vertices a) write apart.
  const std::size_t n = vertices();
  run_parts(host_threads(edges_.size()), [&](int part, int parts) {
    const auto [low, high] = part_range(n, part, parts);
    for (std::size_t a = low; a < high; ++a)
      for (std::size_t e = first_[a]; e < first_[a + 1]; ++e) {
        // The edge lists of later edges' heads, wanted soon (the heads are
        // scattered over the mesh: the loop waits on memory): where one
        // starts, then, once that is known, its edges.
        if (e + 2 * kPrefetchAhead < edges_.size())
          __builtin_prefetch(
              &first_[static_cast<std::size_t>(edges_[e + 2 * kPrefetchAhead].head)]);
        if (e + kPrefetchAhead < edges_.size())
          __builtin_prefetch(
              &edges_[first_[static_cast<std::size_t>(edges_[e + kPrefetchAhead].head)]]);
        const int32_t b = edges_[e].head;
        if (b < static_cast<int32_t>(a))
          continue; // found from b's edges
        if (e > first_[a] && edges_[e - 1].head == b) {
          reverse[e] = reverse[e - 1]; // a repeated edge a -> b
          continue;
        }
        const auto end = edges_.begin() + static_cast<std::ptrdiff_t>(first_[b + 1]);
        auto at = std::lower_bound(edges_.begin() + static_cast<std::ptrdiff_t>(first_[b]), end,
                                   static_cast<int32_t>(a), by_head);
        if (at == end || at->head != static_cast<int32_t>(a))
          continue;
        reverse[e] = at - edges_.begin();
        for (; at != end && at->head == static_cast<int32_t>(a); ++at)
          reverse[static_cast<std::size_t>(at - edges_.begin())] = static_cast<int64_t>(e);
      }
  });
  return reverse;
}

} // namespace clmesh
