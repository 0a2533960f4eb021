// clmesh — triangulate() for an input and options validated already, and
// for several small point sets at once (triangulate_many's packs).
//
// The command line validates each input as soon as it is read, before it
// leases a device for it; validating a mesh of a million triangles again
// (-r) would cost a tenth of a second more.
#pragma once

#include "clmesh/device.hpp"
#include "clmesh/input.hpp"
#include "clmesh/mesh.hpp"
#include "clmesh/options.hpp"

#include <cstddef>
#include <vector>

namespace clmesh {

// triangulate(device, input, options) without its validate(options) and
// validate(input): the caller has run both.
Mesh triangulate_validated(Device &device, const Input &input, const Options &options);

// Point sets of at most this many points pack (the options allowing); a
// pack holds at most kPackMostPoints points and kPackMostInputs inputs, so
// that its arrays stay small and its first results come soon.
constexpr std::size_t kPackedLargest = 65536;
constexpr std::size_t kPackMostPoints = std::size_t{1} << 20, kPackMostInputs = 4096;
// Whether a pack of `inputs` inputs and `points` points is full for an input
// of `more` points.
inline bool pack_full(std::size_t inputs, std::size_t points, std::size_t more) {
  return points + more > kPackMostPoints || inputs >= kPackMostInputs;
}

// Whether the options give a plain Delaunay triangulation, which packs:
// no -p, -r, -q, -a, -D, size field or Voronoi image.
bool options_pack(const Options &options);
// Whether triangulate_packed takes the input (validated, with options that
// pack): at most kPackedLargest points, not all collinear.
bool input_packs(const Input &input);

// The meshes of several inputs (each input_packs, the options pack), each
// the one triangulate_validated gives it alone, from one device mesh and
// one run of the phases (delaunay_packed).
std::vector<Mesh> triangulate_packed(Device &device, const std::vector<const Input *> &inputs,
                                     const Options &options);

} // namespace clmesh
