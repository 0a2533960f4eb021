// clmesh — every device buffer of a run, owned in one place (RAII through cl::Buffer).
#pragma once

#include "clmesh/input.hpp"
#include "runtime/opencl_context.hpp"

#include <algorithm>
#include <cstddef>
#include <initializer_list>
#include <vector>

namespace clmesh {

template <typename T> class DeviceArray {
public:
  DeviceArray() = default;
  // huge_pages: for the mesh's arrays (Device::allocate); kept when the array grows.
  DeviceArray(Device &device, std::size_t size, bool huge_pages = false)
      : size_(size), huge_pages_(huge_pages) {
    buffer_ = guarded("allocation", "allocating a device array",
                      [&] { return device.allocate(sizeof(T) * (size ? size : 1), huge_pages); });
  }
  // The memory of `memory` (a ScratchPool's list) as `size` entries.
  static DeviceArray view(const cl::Buffer &memory, std::size_t size) {
    DeviceArray array;
    array.buffer_ = memory;
    array.size_ = size;
    return array;
  }
  std::size_t size() const { return size_; }
  const cl::Buffer &buffer() const { return buffer_; }
  operator const cl::Buffer &() const { return buffer_; }

  void upload(Device &device, const std::vector<T> &data, std::size_t offset = 0) const {
    if (data.empty())
      return;
    const ProfiledCall timed("blocking write");
    guarded("transfer", "uploading", [&] {
      device.queue().enqueueWriteBuffer(buffer_, CL_TRUE, offset * sizeof(T),
                                        data.size() * sizeof(T), data.data());
    });
  }
  std::vector<T> download(Device &device, std::size_t count, std::size_t offset = 0) const {
    std::vector<T> data(count);
    if (count) {
      const ProfiledCall timed("blocking read");
      guarded("transfer", "downloading", [&] {
        device.queue().enqueueReadBuffer(buffer_, CL_TRUE, offset * sizeof(T), count * sizeof(T),
                                         data.data());
      });
    }
    return data;
  }
  T read(Device &device, std::size_t index) const { return download(device, 1, index)[0]; }
  // Queues the copy of `count` entries from `offset` into `out` without
  // waiting for it: `out` holds them once the queue (in order) has finished
  // this copy, after Device::wait() or a later blocking transfer. Several
  // counts read together cost one wait for the device instead of one each.
  void download_later(Device &device, T *out, std::size_t count, std::size_t offset = 0) const {
    if (count)
      guarded("transfer", "downloading", [&] {
        device.queue().enqueueReadBuffer(buffer_, CL_FALSE, offset * sizeof(T), count * sizeof(T),
                                         out);
      });
  }

  // A larger array holding this one's contents, the rest set to `fill`.
  DeviceArray grown(Device &device, std::size_t size, T fill) const {
    DeviceArray bigger = enlarged(device, size, size_);
    if (size > size_)
      bigger.fill_range(device, fill, size_, size - size_, "allocation");
    return bigger;
  }
  // A larger array holding the first `kept` entries of this one, the rest
  // not written (so not touched: memory comes to a CPU device when first
  // written).
  DeviceArray enlarged(Device &device, std::size_t size, std::size_t kept) const {
    DeviceArray bigger(device, size, huge_pages_);
    if (kept)
      guarded("allocation", "growing a device array", [&] {
        device.queue().enqueueCopyBuffer(buffer_, bigger.buffer_, 0, 0, kept * sizeof(T));
      });
    return bigger;
  }
  void fill(Device &device, T value, std::size_t count) const {
    fill_range(device, value, 0, count, "setup");
  }
  // Entries from `first` on discarded: their memory goes back to the system
  // (Device::discard) and they hold zeros or old values when next read.
  void discard(Device &device, std::size_t first, const char *phase) const {
    if (first < size_)
      device.discard(buffer_, first * sizeof(T), (size_ - first) * sizeof(T), phase);
  }
  // Entries [first, first + count) set to `value`.
  void fill_range(Device &device, T value, std::size_t first, std::size_t count,
                  const char *phase) const {
    device.fill(buffer_, &value, sizeof(T), first * sizeof(T), count * sizeof(T), phase);
  }

private:
  static_assert(sizeof(T) == 4 || sizeof(T) == 8 || sizeof(T) == 16,
                "Device::fill writes elements of 1, 2 or 4 words");

  cl::Buffer buffer_;
  std::size_t size_ = 0;
  bool huge_pages_ = false;
};

// Arrays that are set only as their slots come into use are set this many
// slots ahead of the use, within their capacity: a small mesh's growth takes
// one fill, not one per iteration, and at most this many slots' pages are
// touched early.
constexpr std::size_t kFillAhead = 16384;
inline std::size_t fill_ahead(std::size_t used, std::size_t capacity) {
  return std::min(capacity, used + kFillAhead);
}

// An array of one value (0 by default) as far as its entries come into use:
// cover(n) sets those below n not set yet, kFillAhead beyond, within its
// size, so that the pages past the entries in use are not touched (not
// resident) and a large capacity costs no fill.
template <typename T> struct CoveredArray {
  DeviceArray<T> array;
  T value{};
  std::size_t covered = 0; // entries set
  CoveredArray() = default;
  CoveredArray(Device &device, std::size_t size, T value_ = T{})
      : array(device, size), value(value_) {}
  void cover(Device &device, std::size_t count, const char *phase) {
    if (count <= covered)
      return;
    const std::size_t end = fill_ahead(count, array.size());
    array.fill_range(device, value, covered, end - covered, phase);
    covered = end;
  }
  // A larger array keeping the covered entries.
  void grow(Device &device, std::size_t size) {
    if (size > array.size())
      array = array.enlarged(device, size, covered);
  }
};

// A list on the device that grows (amortised doubling): entries appended
// from other device arrays, or written by kernels into room reserved first.
template <typename T> struct DeviceList {
  DeviceArray<T> items;
  std::size_t size = 0;
  // Room for `count` more entries after the first `size`.
  void reserve(Device &device, std::size_t count) {
    if (size + count > items.size())
      items = items.enlarged(device, 2 * (size + count), size);
  }
  void append(Device &device, const DeviceArray<T> &from, std::size_t count) {
    if (count == 0)
      return;
    reserve(device, count);
    guarded("transfer", "appending to a device list", [&] {
      device.queue().enqueueCopyBuffer(from.buffer(), items.buffer(), 0, size * sizeof(T),
                                       count * sizeof(T));
    });
    size += count;
  }
};

// The triangulation and the per-point state that stay resident on the device
// from upload to download (thesis §2.2 data structure). Its arrays (and those
// that take their place) ask for huge pages (Device::allocate).
struct DeviceMesh {
  static constexpr bool kHugePages = true;

  // Room for the input points and `extra_points` points added later (the
  // intersections of crossing segments).
  DeviceMesh(Device &device, std::size_t point_count, std::size_t extra_points = 0);

  std::size_t point_capacity;
  std::size_t point_count;       // points in use: the input, then the added ones
  std::size_t triangle_capacity; // 2 capacity + 2 slots: ghosts included, enough for every point
  std::size_t list_capacity;     // active and scratch lists

  DeviceArray<cl_double2> points;      // in spatial (Hilbert) order
  DeviceArray<cl_int> original_id;     // input index of each device point
  DeviceArray<cl_int> tri_vertex;      // 3 per triangle
  DeviceArray<cl_int> tri_neighbor;    // 3 per triangle, (triangle << 2) | edge
  DeviceArray<cl_int> tri_mark;        // atomic-minimum marks (unsigned on the device)
  DeviceArray<cl_int> modified_stamp;  // step that last rewrote the slot
  DeviceArray<cl_int> children;        // 3 per triangle: its replacements
  DeviceArray<cl_int> vertex_triangle; // one incident triangle per vertex
  DeviceArray<cl_int> duplicate_of;
  DeviceArray<cl_int> location;      // containing triangle of each point not yet inserted
  DeviceArray<cl_int> location_edge; // -1 or the edge the point lies on
  // Constraints (CDT) as compressed rows per vertex, both directions. The
  // rows exist once set_constraint_rows has set them (point_capacity + 1
  // starts); before, constraint_start is one unused entry, which the kernels
  // do not read while has_constraints is false.
  DeviceArray<cl_int> constraint_start;
  DeviceArray<cl_int> constraint_adjacent; // 2 per constraint
  DeviceArray<cl_int> constraint_segment;  // per entry of constraint_adjacent: its constraint
  bool has_constraints = false;            // any row not empty
  bool has_constraint_rows() const { return constraint_start.size() > 1; }
  cl_int constraint_entries = 0; // entries of constraint_adjacent: where rows end
  // The region of each triangle slot (-1: none; triangle_capacity entries)
  // once has_regions, else one unused entry (cl/mesh_params.h).
  DeviceArray<cl_int> tri_region;
  bool has_regions = false;

  // Uploads `segments` (device point numbers, distinct, none of zero length)
  // as the constraint rows (none: empty rows).
  void set_constraint_rows(Device &device, const std::vector<Segment> &segments);

  // duplicate_of (-1: none) and the constraint rows (empty) hold their
  // first values for the points below points_filled; those past it are set
  // only when the points come into use (fill_point_slots, before
  // point_count passes them, kFillAhead ahead), so that the pages past the
  // points in use are not touched (not resident). The points added later write their other
  // arrays themselves (location, the refinement's state...).
  std::size_t points_filled = 0;
  // Points [points_filled, count) set so.
  void fill_point_slots(Device &device, std::size_t count);

  std::size_t triangle_count = 0; // slots in use or freed (DT and CDT never delete)

  // tri_mark holds no mark and modified_stamp 0 in the slots that were never
  // used, below triangles_filled; the slots past it are set only when they
  // come into use (fill_triangle_slots, before triangle_count passes them,
  // kFillAhead ahead), so that their pages are not touched (not resident)
  // before.
  std::size_t triangles_filled = 0;
  // Slots [triangles_filled, slots) set so (from the first slot after
  // clear_triangle_slots).
  void fill_triangle_slots(Device &device, std::size_t slots);
  // Every slot to be set again when it comes into use.
  void clear_triangle_slots() { triangles_filled = 0; }

  // Empty slots (thesis §3.6.1), in slot order: free_triangles[free_first ..
  // free_first + free_count), likewise for points. Refinement deletes
  // triangles and points and collects them here when the room past
  // triangle_count / point_count runs short.
  struct FreeList {
    DeviceArray<cl_int> slots;
    std::size_t first = 0, count = 0;
    // Takes `wanted` slots: the free ones first. Returns how many new slots
    // (past the end of the used range) the batch needs.
    std::size_t take(std::size_t wanted);
  };
  FreeList free_triangles, free_points;

  // Refinement only (allocated by enable_refinement): per point its state
  // (cl/refinement.h), insertion radius squared and priority (thesis §3.3,
  // §3.5), and the segment it lies on (cl/refinement.h point_segment); the
  // two ends of each segment.
  DeviceArray<cl_int> point_state;
  DeviceArray<cl_double> insertion_radius2;
  DeviceArray<cl_uint> point_priority;
  DeviceArray<cl_int> point_segment;
  DeviceArray<cl_int> segment_end;
  void enable_refinement(Device &device);
  // Refinement of a PSLG: the segments as they stand in the mesh (device
  // numbering) become the constraint rows and segment_end, and the input
  // vertices where two or more meet are marked (CLM_SEGMENT_JOINT).
  void set_segments(Device &device, const std::vector<Segment> &segments);

  // Set the buffers of CLM_TRIANGULATION_PARAMS, or of CLM_MESH_PARAMS (the
  // same and the refinement-only ones; after enable_refinement), in the
  // order of cl/mesh_params.h, as the arguments of `kernel` from index
  // `first` on; return the index after them. Bound at every launch: growing
  // and refinement swap the buffers.
  cl_uint bind_triangulation(cl::Kernel &kernel, cl_uint first) const;
  cl_uint bind(cl::Kernel &kernel, cl_uint first) const;

  // Every array but those in `kept` gives its memory back to the system
  // (DeviceArray::discard): the mesh's last use is over but for them.
  void discard_except(Device &device, std::initializer_list<const DeviceArray<cl_int> *> kept);

  // Makes room for `extra_points` more points (and their triangles), keeping
  // every array's contents (thesis §3.6.1: arrays expand when slots run out).
  void grow(Device &device, std::size_t extra_points);
};

} // namespace clmesh
