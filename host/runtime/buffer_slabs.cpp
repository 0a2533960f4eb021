// clmesh — small device buffers carved out of slabs (see buffer_slabs.hpp).
#include "runtime/buffer_slabs.hpp"

#include <algorithm>
#include <mutex>
#include <vector>

namespace clmesh {

namespace {

// Each slab holds this many bytes; pieces are powers of two from the
// alignment up to kLargest, each size class with a list of free pieces.
constexpr std::size_t kSlabBytes = std::size_t{16} << 20;

struct Piece {
  std::size_t slab, offset;
};

} // namespace

struct BufferSlabs::State {
  cl::Context context;
  std::size_t alignment, most_slabs;
  std::mutex mutex; // pieces come back on a driver's thread
  std::vector<cl::Buffer> slabs;
  std::size_t used_in_last = kSlabBytes; // bytes handed out of the last slab
  std::vector<std::vector<Piece>> free;  // by size class

  // The size class of `bytes`: the piece is alignment << class bytes.
  std::size_t size_class(std::size_t bytes) const {
    std::size_t k = 0;
    while ((alignment << k) < bytes)
      ++k;
    return k;
  }
};

namespace {

// What a piece's release callback needs.
struct Release {
  std::shared_ptr<BufferSlabs::State> state;
  std::size_t size_class;
  Piece piece;
};

} // namespace

BufferSlabs::BufferSlabs(const cl::Context &context, std::size_t alignment, std::size_t most_bytes)
    : state_(std::make_shared<State>()) {
  state_->context = context;
  state_->alignment = std::max<std::size_t>(alignment, 256);
  state_->most_slabs = most_bytes / kSlabBytes;
  state_->free.resize(state_->size_class(kLargest) + 1);
}

cl::Buffer BufferSlabs::take(std::size_t bytes) {
  State &state = *state_;
  const std::size_t size_class = state.size_class(bytes);
  const std::size_t length = state.alignment << size_class;
  Piece piece{};
  cl_mem slab = nullptr;
  {
    const std::lock_guard<std::mutex> lock(state.mutex);
    std::vector<Piece> &free = state.free[size_class];
    if (!free.empty()) {
      piece = free.back();
      free.pop_back();
    } else {
      // Pieces of a slab go in order, each aligned to its own length (a
      // power of two times the alignment, dividing the slab's length).
      std::size_t offset = (state.used_in_last + length - 1) / length * length;
      if (offset + length > kSlabBytes) {
        if (state.slabs.size() >= state.most_slabs)
          return cl::Buffer();
        cl::Buffer fresh;
        try {
          fresh = cl::Buffer(state.context, CL_MEM_READ_WRITE, kSlabBytes);
        } catch (const cl::Error &) {
          return cl::Buffer(); // the driver's own buffers then
        }
        state.slabs.push_back(fresh);
        offset = 0;
      }
      piece = {state.slabs.size() - 1, offset};
      state.used_in_last = offset + length;
    }
    slab = state.slabs[piece.slab]();
  }
  const cl_buffer_region region{piece.offset, bytes};
  cl_int error = CL_SUCCESS;
  cl_mem sub =
      clCreateSubBuffer(slab, CL_MEM_READ_WRITE, CL_BUFFER_CREATE_TYPE_REGION, &region, &error);
  auto *release = new Release{state_, size_class, piece};
  auto give_back = [](cl_mem, void *user_data) {
    const auto *owned = static_cast<Release *>(user_data);
    {
      const std::lock_guard<std::mutex> lock(owned->state->mutex);
      owned->state->free[owned->size_class].push_back(owned->piece);
    }
    delete owned;
  };
  if (error == CL_SUCCESS &&
      clSetMemObjectDestructorCallback(sub, give_back, release) == CL_SUCCESS)
    return cl::Buffer(sub);
  if (error == CL_SUCCESS)
    clReleaseMemObject(sub);
  {
    const std::lock_guard<std::mutex> lock(state.mutex);
    state.free[size_class].push_back(piece);
  }
  delete release;
  return cl::Buffer();
}

} // namespace clmesh
