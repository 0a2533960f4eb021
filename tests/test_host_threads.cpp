// The host's loops cut into parts (runtime/host_threads.hpp): every item in
// exactly one part, both parts run, and what a part throws reaches the caller.
#include "runtime/host_threads.hpp"

#include <doctest/doctest.h>

#include <stdexcept>
#include <vector>

TEST_CASE("host threads: the parts cover every item once") {
  for (const std::size_t n : {std::size_t{0}, std::size_t{1}, std::size_t{7}, std::size_t{100001}})
    for (const int parts : {1, 2}) {
      std::vector<int> seen(n, 0);
      clmesh::run_parts(parts, [&](int part, int count) {
        CHECK(count == parts);
        const auto [first, end] = clmesh::part_range(n, part, count);
        CHECK(first <= end);
        for (std::size_t i = first; i < end; ++i)
          ++seen[i];
      });
      for (std::size_t i = 0; i < n; ++i)
        REQUIRE(seen[i] == 1);
    }
}

TEST_CASE("host threads: a part's exception reaches the caller after both parts ran") {
  for (const int failing : {0, 1}) {
    std::vector<int> ran(2, 0);
    CHECK_THROWS_AS(clmesh::run_parts(2,
                                      [&](int part, int) {
                                        ran[static_cast<std::size_t>(part)] = 1;
                                        if (part == failing)
                                          throw std::runtime_error("part failed");
                                      }),
                    std::runtime_error);
    CHECK(ran[0] == 1);
    CHECK(ran[1] == 1);
  }
}

TEST_CASE("host threads: few items take one part") {
  CHECK(clmesh::host_threads(clmesh::kManyItems) == 1);
  CHECK(clmesh::host_threads(0) == 1);
}
