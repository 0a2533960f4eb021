// clmesh — small device buffers carved out of a few large ones (the GPU
// paths). A small mesh asks for a few hundred buffers, and a GPU driver's
// allocation and release of device memory cost far more than a sub-buffer
// of memory it holds already; the slabs keep that memory from input to
// input.
#pragma once

#include <CL/opencl.hpp>

#include <cstddef>
#include <memory>

namespace clmesh {

class BufferSlabs {
public:
  // Buffers of at most this many bytes come from the slabs.
  static constexpr std::size_t kLargest = std::size_t{1} << 20;

  // alignment: CL_DEVICE_MEM_BASE_ADDR_ALIGN in bytes (a sub-buffer's
  // origin must be a multiple of it); at most `most_bytes` of slabs.
  BufferSlabs(const cl::Context &context, std::size_t alignment, std::size_t most_bytes);

  // A read-write sub-buffer of `bytes` (1 to kLargest), or a null buffer
  // when the slabs are full (the caller then asks the driver). Its piece of
  // slab returns for the next buffer of its size class once the driver has
  // deleted it (all its commands done). The pieces of one BufferSlabs are
  // for one command queue: on PoCL, sub-buffers of one buffer used from two
  // queues at once crash kernels.
  cl::Buffer take(std::size_t bytes);

  struct State; // shared with the pieces' release callbacks

private:
  std::shared_ptr<State> state_;
};

} // namespace clmesh
