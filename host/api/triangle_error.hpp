// clmesh — errors about a triangle of a mesh to refine (-r).
#pragma once

#include "clmesh/input.hpp"

#include <cstddef>
#include <string>

namespace clmesh {

// Throws an InputError about input.triangles[t]: at its line of
// input.triangles_source when the triangles came from a file, numbered as
// the file numbers them.
[[noreturn]] void throw_triangle_error(const Input &input, std::size_t t,
                                       const std::string &problem);

} // namespace clmesh
