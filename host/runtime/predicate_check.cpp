#include "runtime/predicate_check.hpp"

#include "runtime/device_mesh.hpp"
#include "runtime/opencl_context.hpp"

#include "predicates.h"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>

namespace clmesh {
namespace {

const char *kFile = "predicate_check.cl";
const char *kPhase = "setup";
constexpr int kSigns = 5; // per case, in the order of evaluate_predicates

// Quadrilaterals of a refined mesh (Triangle's A.poly, -pcq30) whose in-circle
// determinants are about 1e-22: triangle a, b, c and the vertex d opposite.
// A device whose exact stage was wrong chose the other diagonal of each.
const PredicateCase kRefinedQuads[] = {
    {0x1.80a25482c6ce6p-2, -0x1.b8d858d412532p-2, 0x1.8ff6ba48267dbp-2, -0x1.c00068102f98ap-2,
     0x1.9d9bbe905e037p-2, -0x1.7fc788a9b40a9p-2, 0x1.a91b0ae465c6ep-2, -0x1.85259416c9feap-2},
    {0x1.db63ac1ce4596p-2, -0x1.0f6fec23fecacp-2, 0x1.e7f5d46b03fe0p-2, -0x1.e405044e97fb8p-3,
     0x1.e60b47b258082p-2, -0x1.e23b007f90aa2p-3, 0x1.d78e92ab8c6d9p-2, -0x1.0da5e854f7796p-2},
    {0x1.1c68de619b448p-1, -0x1.499626a6dfc60p-2, 0x1.1ff05ac746ffep-1, -0x1.463175f72a580p-2,
     0x1.1132c006a8d31p-1, -0x1.0d634710e1c46p-2, 0x1.0f6f01d3d2f57p-1, -0x1.0f159f68bc7b6p-2},
    {0x1.0f6f01d3d2f57p-1, -0x1.0f159f68bc7b6p-2, 0x1.1132c006a8d31p-1, -0x1.0d634710e1c46p-2,
     0x1.09d3f2a659bcbp-1, -0x1.e1f85f3b7af52p-3, 0x1.08f2138ceecdep-1, -0x1.e3aab79355ac2p-3},
};

std::array<int, kSigns> host_signs(const PredicateCase &p) {
  return {clm_orient2d(p[0], p[1], p[2], p[3], p[4], p[5]),
          clm_orient2d_exact(p[0], p[1], p[2], p[3], p[4], p[5]),
          clm_incircle(p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7]),
          clm_incircle_after_filter(p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7]),
          clm_incircle_sos(p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7])};
}

const char *kSignNames[kSigns] = {"orient2d", "exact orient2d", "incircle", "exact incircle",
                                  "perturbed incircle"};

} // namespace

std::vector<PredicateCase> hard_predicate_cases() {
  std::vector<PredicateCase> cases(std::begin(kRefinedQuads), std::end(kRefinedQuads));
  // Four points each rounded from one circle: cocircular up to rounding, so
  // the in-circle filter fails and the exact stages decide. The coordinates
  // only need to be the same on host and device, not on every host.
  for (int k = 0; k < 96; ++k) {
    const double cx = 0.3 + 0.011 * k, cy = 0.7 - 0.0037 * k, r = 0.03 + 0.0013 * (k % 7);
    PredicateCase c{};
    for (int j = 0; j < 4; ++j) {
      const double angle = 6.283185307179586 * (0.25 * j + 0.03 * ((k * (j + 1)) % 5));
      c[2 * j] = cx + r * std::cos(angle);
      c[2 * j + 1] = cy + r * std::sin(angle);
    }
    cases.push_back(c);
  }
  // Shewchuk's near-collinear grid: a a few ulps from the line through b and c.
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j)
      cases.push_back({0.5 + i * 0x1p-53, 0.5 + j * 0x1p-53, 12, 12, 24, 24, 0.5, 0.75});
  // Exactly cocircular lattice points (in-circle 0, decided by the
  // perturbation), and collinear ones.
  cases.push_back({0, 0, 1, 0, 1, 1, 0, 1});
  cases.push_back({3, 4, -4, 3, -3, -4, 5, 0});
  cases.push_back({0, 0, 1, 1, 2, 2, 3, 3});
  // Everything again at small and large magnitudes (powers of two: the same
  // signs, other exponents).
  const std::size_t base = cases.size();
  for (const double scale : {0x1p-120, 0x1p+120})
    for (std::size_t k = 0; k < base; ++k) {
      PredicateCase c = cases[k];
      for (double &v : c)
        v *= scale;
      cases.push_back(c);
    }
  return cases;
}

void check_device_predicates(Device &device) {
  if (const char *env = std::getenv("CLMESH_PREDICATE_CHECK"); env && std::strcmp(env, "off") == 0)
    return;
  const std::vector<PredicateCase> cases = hard_predicate_cases();
  std::vector<cl_double> coords;
  for (const PredicateCase &c : cases)
    coords.insert(coords.end(), c.begin(), c.end());
  // A pass is kept in the program cache, keyed by the check's program as the
  // device builds it and by the cases: later runs with the same sources,
  // options, device and driver skip the check.
  const ProgramCache verdict = device.result_cache(
      kFile, "passed: " + std::string(reinterpret_cast<const char *>(coords.data()),
                                      coords.size() * sizeof(cl_double)));
  if (verdict.load())
    return;
  const DeviceArray<cl_double> device_coords(device, coords.size());
  device_coords.upload(device, coords);
  const DeviceArray<cl_int> signs(device, kSigns * cases.size());
  cl::Kernel kernel = device.kernel(kFile, "evaluate_predicates", kPhase);
  set_args(kernel, device_coords.buffer(), signs.buffer(), static_cast<cl_int>(cases.size()));
  launch(device, kernel, cases.size(), kPhase);
  const std::vector<cl_int> got = signs.download(device, signs.size());
  std::size_t wrong = 0, first_case = 0;
  int first_sign = 0;
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const auto expected = host_signs(cases[k]);
    for (int s = 0; s < kSigns; ++s)
      if (got[kSigns * k + s] != expected[s] && wrong++ == 0) {
        first_case = k;
        first_sign = s;
      }
  }
  if (wrong > 0)
    throw DeviceError("device '" + device.description().device_name +
                      "' gets the exact predicates wrong (" + std::to_string(wrong) + " of " +
                      std::to_string(kSigns * cases.size()) + " signs, first the " +
                      kSignNames[first_sign] + " of case " + std::to_string(first_case) +
                      "): its OpenCL compiler does not keep their arithmetic exact, so meshes "
                      "made on it could be wrong; choose another device (clmesh --list-devices)");
  verdict.store({1});
}

} // namespace clmesh
