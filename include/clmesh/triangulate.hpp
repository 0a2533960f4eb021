// clmesh — one call, one input, one mesh (Triangle's triangulate()).
#pragma once

#include "clmesh/device.hpp"
#include "clmesh/input.hpp"
#include "clmesh/mesh.hpp"
#include "clmesh/options.hpp"

#include <string>

namespace clmesh {

// The mesh of `input` with `options`: the Delaunay triangulation of the
// points (GPU-DT), with -p the constrained Delaunay triangulation of the PSLG
// (GPU-CDT, exterior and holes removed unless -c/-O), with -q/-a a quality
// mesh of the point set (GPU-QM-V, or GPU-QM by options.tuning). The same
// input and options give the same mesh on every run.
// Throws InputError, OptionError, DeviceError, OpenCLError.
Mesh triangulate(Device &device, const Input &input, const Options &options);
// The same with Triangle's switch letters: triangulate(device, input, "pq30").
Mesh triangulate(Device &device, const Input &input, const std::string &switches);
// On the device options.device names, opened once per process (whichever
// spec names it); calls from several threads take the device one at a time.
Mesh triangulate(const Input &input, const Options &options);

} // namespace clmesh
