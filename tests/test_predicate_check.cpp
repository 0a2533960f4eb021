// The device's check of its exact predicates (runtime/predicate_check.hpp):
// its cases reach the exact stages, and the test device passes it.
#include <doctest/doctest.h>

#include "runtime/opencl_context.hpp"
#include "runtime/predicate_check.hpp"
#include "test_support.hpp"

#include "predicates.h"

TEST_CASE("predicate check: the cases reach the exact stages and the perturbation") {
  const auto cases = clmesh::hard_predicate_cases();
  int orient_uncertain = 0, incircle_uncertain = 0, collinear = 0, cocircular = 0;
  for (const auto &p : cases) {
    orient_uncertain += clm_orient2d_filter(p[0], p[1], p[2], p[3], p[4], p[5]) == CLM_UNCERTAIN;
    incircle_uncertain +=
        clm_incircle_filter(p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7]) == CLM_UNCERTAIN;
    collinear += clm_orient2d(p[0], p[1], p[2], p[3], p[4], p[5]) == 0;
    cocircular += clm_incircle(p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7]) == 0;
  }
  MESSAGE(cases.size() << " cases: " << orient_uncertain << " orientations and "
                       << incircle_uncertain << " in-circle tests past the filter, " << collinear
                       << " collinear, " << cocircular << " cocircular");
  CHECK(orient_uncertain >= 100);
  CHECK(incircle_uncertain >= 200);
  CHECK(collinear >= 3);
  CHECK(cocircular >= 6);
}

TEST_CASE("predicate check: the test device computes every sign as the host does") {
  // With the program cache off, so that no pass kept from an earlier run stands in.
  const test_support::Environment no_cache("CLMESH_CACHE_DIR", "");
  CHECK_NOTHROW(clmesh::check_device_predicates(test_support::device()));
}
