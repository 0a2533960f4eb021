// clmesh — one call, one input, one mesh (Triangle's triangulate()); and
// triangulate_many(), one call, many inputs on one device.
#pragma once

#include "clmesh/device.hpp"
#include "clmesh/input.hpp"
#include "clmesh/mesh.hpp"
#include "clmesh/options.hpp"

#include <cstddef>
#include <exception>
#include <functional>
#include <string>
#include <vector>

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
// When nothing names a device (options.device "", CLMESH_DEVICE and
// POCL_DEVICES unset), the first such call asks PoCL for its in-thread
// driver beside its multi-threaded one; on PoCL, inputs below 100,000
// points, segments and triangles then run on the in-thread device (the same
// mesh, fewer costs per kernel launch).
Mesh triangulate(const Input &input, const Options &options);

// One input's outcome in triangulate_many(): its mesh, or the error that
// stopped it.
struct BatchResult {
  Mesh mesh;                // empty when the input failed
  std::exception_ptr error; // null when the input was meshed; rethrow it for its type
  std::string message;      // the error's message ("" when meshed)
  bool ok() const { return !error; }
};

// Every input meshed with the same options on one device, whose context and
// built programs serve them all; results[i] is the mesh triangulate(device,
// inputs[i], options) gives, or the error it throws (InputError,
// DeviceError, OpenCLError...), and the other inputs go on. Throws only
// OptionError, before meshing anything, when the options are invalid.
std::vector<BatchResult> triangulate_many(Device &device, const std::vector<Input> &inputs,
                                          const Options &options);
// The same with Triangle's switch letters.
std::vector<BatchResult> triangulate_many(Device &device, const std::vector<Input> &inputs,
                                          const std::string &switches);
// The streaming form, for batches too large to hold at once: meshes inputs 0
// to count - 1 in order, input(i) giving the i-th (an error it throws, say a
// file that cannot be read, becomes that input's) and done(i, result) taking
// each result as soon as it is ready. Errors done() throws end the batch.
void triangulate_many(Device &device, std::size_t count,
                      const std::function<Input(std::size_t)> &input, const Options &options,
                      const std::function<void(std::size_t, BatchResult &&)> &done);
// Both forms on the device triangulate(input, options) would take for each
// input: set up once per process, and held input by input (calls from other
// threads may go between two inputs), or on streams of it (Tuning::streams,
// by default on a GPU), which are the batch's own. Throw OptionError, then DeviceError
// when no device matches, before meshing anything.
std::vector<BatchResult> triangulate_many(const std::vector<Input> &inputs, const Options &options);
void triangulate_many(std::size_t count, const std::function<Input(std::size_t)> &input,
                      const Options &options,
                      const std::function<void(std::size_t, BatchResult &&)> &done);

} // namespace clmesh
