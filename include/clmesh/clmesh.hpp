// clmesh — everything a user of the library needs:
//
//   auto device = clmesh::open_device();
//   clmesh::Input input;
//   input.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
//   clmesh::Mesh mesh = clmesh::triangulate(*device, input, "q30a0.01");
#pragma once

#include "clmesh/check.hpp"
#include "clmesh/device.hpp"
#include "clmesh/errors.hpp"
#include "clmesh/geometry.hpp"
#include "clmesh/input.hpp"
#include "clmesh/io.hpp"
#include "clmesh/mesh.hpp"
#include "clmesh/options.hpp"
#include "clmesh/report.hpp"
#include "clmesh/size_field.hpp"
#include "clmesh/statistics.hpp"
#include "clmesh/triangulate.hpp"
#include "clmesh/tuning.hpp"
#include "clmesh/version.hpp"
