// clmesh — triangulate_many's streams (see stream_pool.hpp).
#include "api/stream_pool.hpp"

#include "runtime/opencl_context.hpp"

#include <algorithm>
#include <utility>

namespace clmesh {

BatchResult failure() {
  BatchResult result;
  result.error = std::current_exception();
  try {
    throw;
  } catch (const std::exception &error) {
    result.message = error.what();
  }
  return result;
}

std::size_t default_streams(std::size_t cpus) { return std::clamp<std::size_t>(cpus, 4, 16); }

std::size_t streams_on(const Device &device, const Options &options) {
  if (options.tuning.streams > 0)
    return device.takes_streams() ? options.tuning.streams : 1;
  if (device.cpu_paths() || !device.takes_streams())
    return 1;
  return default_streams(std::thread::hardware_concurrency());
}

// Results that may wait for an earlier input, a multiple of the streams:
// a slow input holds up the hand-off, not the memory.
constexpr std::size_t kWaitingPerStream = 4;

StreamPool::StreamPool(std::size_t streams, const Attempt &attempt, const Done &done)
    : streams_(std::max<std::size_t>(streams, 1)), attempt_(attempt), done_(done) {
  for (std::size_t t = 0; t < streams_; ++t)
    threads_.emplace_back([this] { run(); });
}

StreamPool::~StreamPool() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
    jobs_.clear();
  }
  changed_.notify_all();
  for (std::thread &thread : threads_)
    thread.join();
}

void StreamPool::submit(std::size_t i, Input input, Device &device, std::mutex *busy) {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    hand_on(lock);
    if (meshing_.size() < streams_ && finished_.size() < kWaitingPerStream * streams_)
      break;
    changed_.wait(lock);
  }
  std::vector<std::shared_ptr<Device>> &idle = idle_[&device];
  std::shared_ptr<Device> stream;
  if (!idle.empty()) {
    stream = std::move(idle.back());
    idle.pop_back();
  } else {
    // Fewer than `streams_` of this device are busy: one more is made (the
    // device itself idle meanwhile, or held through `busy`).
    try {
      std::unique_lock<std::mutex> held;
      if (busy)
        held = std::unique_lock<std::mutex>(*busy);
      stream = open_stream(device);
    } catch (const std::exception &) { // the input's error
      finished_.emplace(i, failure());
      return;
    }
  }
  meshing_.insert(i);
  jobs_.push_back({i, std::move(input), &device, std::move(stream)});
  lock.unlock();
  changed_.notify_all();
}

void StreamPool::drain() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    hand_on(lock);
    if (meshing_.empty() && finished_.empty())
      return;
    changed_.wait(lock);
  }
}

void StreamPool::run() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    changed_.wait(lock, [this] { return stopping_ || !jobs_.empty(); });
    if (jobs_.empty())
      return; // stopping
    Job job = std::move(jobs_.front());
    jobs_.pop_front();
    lock.unlock();
    BatchResult result = attempt_(*job.stream, job.input);
    lock.lock();
    idle_[job.device].push_back(std::move(job.stream));
    meshing_.erase(job.index);
    finished_.emplace(job.index, std::move(result));
    changed_.notify_all();
  }
}

void StreamPool::hand_on(std::unique_lock<std::mutex> &lock) {
  while (!finished_.empty() && (meshing_.empty() || finished_.begin()->first < *meshing_.begin())) {
    auto first = finished_.begin();
    const std::size_t index = first->first;
    BatchResult result = std::move(first->second);
    finished_.erase(first);
    lock.unlock();
    done_(index, std::move(result));
    lock.lock();
  }
}

} // namespace clmesh
