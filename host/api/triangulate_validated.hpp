// clmesh — triangulate() for an input and options validated already.
//
// The command line validates each input as soon as it is read, before it
// leases a device for it; validating a mesh of a million triangles again
// (-r) would cost a tenth of a second more.
#pragma once

#include "clmesh/device.hpp"
#include "clmesh/input.hpp"
#include "clmesh/mesh.hpp"
#include "clmesh/options.hpp"

namespace clmesh {

// triangulate(device, input, options) without its validate(options) and
// validate(input): the caller has run both.
Mesh triangulate_validated(Device &device, const Input &input, const Options &options);

} // namespace clmesh
