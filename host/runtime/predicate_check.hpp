// clmesh — the device's exact predicates checked against the host's
// (cl/predicate_check.cl).
#pragma once

#include <array>
#include <vector>

namespace clmesh {

class Device;

// Points a, b, c, d of one hard case: nearly collinear, nearly or exactly
// cocircular, at small and large magnitudes.
using PredicateCase = std::array<double, 8>;

// The cases the check evaluates, the same on every run.
std::vector<PredicateCase> hard_predicate_cases();

// Has `device` evaluate the exact predicates on hard_predicate_cases() and
// compares every sign with the host's (cl/predicates.h compiled here without
// contraction). Throws DeviceError naming the device and the first case that
// differs: its compiler does not keep the arithmetic exact, and meshes made
// on it could be wrong or never finish. CLMESH_PREDICATE_CHECK=off skips the
// check (for developers studying such a device).
void check_device_predicates(Device &device);

} // namespace clmesh
