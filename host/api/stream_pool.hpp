// clmesh — triangulate_many's streams: inputs meshed at once, each on a
// thread of its own and a stream of its device (open_stream), their results
// handed on in input order by the caller's thread.
#pragma once

#include "clmesh/device.hpp"
#include "clmesh/input.hpp"
#include "clmesh/options.hpp"
#include "clmesh/triangulate.hpp"

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <thread>
#include <vector>

namespace clmesh {

// The result of the error being handled (a std::exception), as
// triangulate_many reports an input's failure.
BatchResult failure();

// Streams for a GPU with `cpus` CPUs to drive them: one each, at least 4
// (the launches of a few overlap even on few CPUs), at most 16.
std::size_t default_streams(std::size_t cpus);

// How many streams triangulate_many runs on `device`: Tuning::streams, or
// by default, on a device that takes the GPU paths and streams, one per
// hardware thread (at least 4, at most 16), else 1 (a CPU's cores are
// better spent within each mesh).
std::size_t streams_on(const Device &device, const Options &options);

class StreamPool {
public:
  using Done = std::function<void(std::size_t, BatchResult &&)>;
  // An input's result on a device (its error caught into it).
  using Attempt = std::function<BatchResult(Device &, const Input &)>;
  // Up to `streams` inputs at once, each meshed by attempt() on a thread;
  // done(i, result) is called on the caller's thread (within submit() and
  // drain()), in input order.
  StreamPool(std::size_t streams, const Attempt &attempt, const Done &done);
  // Waits for the inputs being meshed (their results are dropped).
  ~StreamPool();
  StreamPool(const StreamPool &) = delete;
  StreamPool &operator=(const StreamPool &) = delete;

  // Meshes input i on a stream of `device`, made while `busy` (when not
  // null) is held; inputs go in increasing order. Waits while every stream
  // is busy or many results wait for an earlier one, handing on those ready.
  void submit(std::size_t i, Input input, Device &device, std::mutex *busy);
  // Waits for every input submitted and hands on their results.
  void drain();

private:
  struct Job {
    std::size_t index;
    Input input;
    Device *device;
    std::shared_ptr<Device> stream;
  };

  void run();
  // Hands on, in order, the results no input still being meshed precedes
  // (the lock held on entry and on return, released for done()).
  void hand_on(std::unique_lock<std::mutex> &lock);

  const std::size_t streams_;
  const Attempt &attempt_;
  const Done &done_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Job> jobs_;
  std::set<std::size_t> meshing_;                                 // submitted, not done
  std::map<std::size_t, BatchResult> finished_;                   // done, not handed on
  std::map<Device *, std::vector<std::shared_ptr<Device>>> idle_; // streams by device
  bool stopping_ = false;
  std::vector<std::thread> threads_;
};

} // namespace clmesh
