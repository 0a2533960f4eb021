// clmesh — many inputs, one device: triangulate() on each, every input's
// error kept in its own result instead of ending the batch. Small point sets
// meshed with plain Delaunay options go in packs, many meshes to one device
// mesh and one run of the phases (triangulate_packed): the same meshes,
// far fewer launches. On a GPU the other inputs are meshed several at once,
// each on a stream of its own (stream_pool.hpp).
#include "api/device_choice.hpp"
#include "api/shared_device.hpp"
#include "api/stream_pool.hpp"
#include "api/triangulate_validated.hpp"
#include "clmesh/device.hpp"
#include "clmesh/errors.hpp"
#include "clmesh/triangulate.hpp"
#include "runtime/opencl_context.hpp"

#include <memory>
#include <mutex>
#include <optional>
#include <utility>

namespace clmesh {

namespace {

// The mesh of the input `input_of()` gives, or the error that stopped it.
template <class InputOf>
BatchResult attempt(Device &device, const InputOf &input_of, const Options &options) {
  BatchResult result;
  try {
    result.mesh = triangulate(device, input_of(), options);
  } catch (const std::exception &) {
    result = failure();
  }
  return result;
}

using Done = std::function<void(std::size_t, BatchResult &&)>;
// Runs work(device) on the device for a pack whose first input is given.
using OnDevice = std::function<void(const Input &first, const std::function<void(Device &)> &work)>;

// The inputs of a pack, gathered in input order until it is full or an
// input that does not pack comes; flush() meshes them and hands each
// result to done(), in input order.
class Pack {
public:
  Pack(const Options &options, const Done &done, const OnDevice &on_device)
      : options_(options),
        packs_(options_pack(options) && options.tuning.packing != Packing::never), done_(done),
        on_device_(on_device) {}

  // Takes input i (a copy) when it packs, after flushing a full pack;
  // false: it does not pack. Throws the input's validation error.
  bool take(std::size_t i, const Input &input) {
    if (!packs_ || input.points.size() > kPackedLargest)
      return false;
    validate(input);
    if (!input_packs(input))
      return false;
    if (pack_full(inputs_.size(), points_, input.points.size()))
      flush();
    points_ += input.points.size();
    indices_.push_back(i);
    inputs_.push_back(input);
    return true;
  }

  void flush() {
    if (inputs_.empty())
      return;
    std::vector<BatchResult> results(inputs_.size());
    try {
      on_device_(inputs_.front(), [&](Device &device) { mesh(device, results); });
    } catch (const std::exception &) { // the device could not be had: every input's error
      for (BatchResult &result : results)
        result = failure();
    }
    for (std::size_t k = 0; k < inputs_.size(); ++k)
      done_(indices_[k], std::move(results[k]));
    inputs_.clear();
    indices_.clear();
    points_ = 0;
  }

private:
  bool packs_on(const Device &device) const {
    switch (options_.tuning.packing) {
    case Packing::always:
      return true;
    case Packing::never:
      return false;
    case Packing::automatic:
      break;
    }
    return !device.cpu_paths();
  }

  void mesh(Device &device, std::vector<BatchResult> &results) {
    if (inputs_.size() > 1 && packs_on(device))
      try {
        std::vector<const Input *> pointers;
        for (const Input &input : inputs_)
          pointers.push_back(&input);
        std::vector<Mesh> meshes = triangulate_packed(device, pointers, options_);
        for (std::size_t k = 0; k < meshes.size(); ++k)
          results[k].mesh = std::move(meshes[k]);
        return;
      } catch (const std::exception &) {
        // Each alone then, with an error of its own where it fails.
      }
    for (std::size_t k = 0; k < inputs_.size(); ++k)
      results[k] = attempt(
          device, [&]() -> const Input & { return inputs_[k]; }, options_);
  }

  const Options &options_;
  const bool packs_;
  const Done &done_;
  const OnDevice &on_device_;
  std::vector<Input> inputs_;
  std::vector<std::size_t> indices_;
  std::size_t points_ = 0;
};

// Where an input that does not pack is meshed: its device, the mutex that
// holds it (null: the caller's device), and how many inputs that device
// meshes at once (streams_on).
struct Target {
  Device *device = nullptr;
  std::mutex *busy = nullptr;
  std::size_t streams = 1;
};

// Inputs 0 .. count - 1 in order: input_of(i) gives input i (an Input or a
// reference to one); those that pack go to the pack that `make_pack(done)`
// makes; the others, on a device of several streams (target_of), to a
// StreamPool, else to alone(input, device, busy, held), which may hold its
// device in `held` until done() returns; an error of input_of(i), of the
// validation or of the device becomes the input's. done() is called in
// input order, on this thread.
template <class InputOf, class MakePack, class TargetOf, class Alone>
void mesh_in_order(std::size_t count, const InputOf &input_of, const Options &options,
                   const Done &done, const MakePack &make_pack, const TargetOf &target_of,
                   const Alone &alone) {
  const StreamPool::Attempt on_stream = [&](Device &device, const Input &input) {
    return attempt(
        device, [&]() -> const Input & { return input; }, options);
  };
  std::unique_ptr<StreamPool> pool; // the streamed inputs' results come first
  auto drain = [&] {
    if (pool)
      pool->drain();
  };
  const Done in_order = [&](std::size_t i, BatchResult &&result) {
    drain();
    done(i, std::move(result));
  };
  Pack pack = make_pack(in_order);
  for (std::size_t i = 0; i < count; ++i) {
    BatchResult result;
    std::unique_lock<std::mutex> held;
    std::optional<Input> streamed;
    Target target;
    try {
      decltype(auto) given = input_of(i);
      if (pack.take(i, given))
        continue;
      pack.flush();
      target = target_of(given);
      if (target.streams > 1)
        streamed = given;
      else
        result = alone(given, *target.device, target.busy, held);
    } catch (const std::exception &) {
      result = failure(); // before the pack's own errors come and go
      pack.flush();
    }
    if (streamed) { // what done() throws, there as here, ends the batch
      if (!pool)
        pool = std::make_unique<StreamPool>(target.streams, on_stream, done);
      pool->submit(i, std::move(*streamed), *target.device, target.busy);
      continue;
    }
    in_order(i, std::move(result)); // the device still held
  }
  pack.flush();
  drain();
}

// mesh_in_order() with every input on `device`.
template <class InputOf>
void mesh_on(Device &device, std::size_t count, const InputOf &input_of, const Options &options,
             const Done &done) {
  const OnDevice on_device = [&](const Input &, const std::function<void(Device &)> &work) {
    work(device);
  };
  const std::size_t streams = streams_on(device, options);
  mesh_in_order(
      count, input_of, options, done,
      [&](const Done &in_order) { return Pack(options, in_order, on_device); },
      [&](const Input &) {
        return Target{&device, nullptr, streams};
      },
      [&](const Input &given, Device &on, std::mutex *, std::unique_lock<std::mutex> &) {
        return attempt(
            on, [&]() -> const Input & { return given; }, options);
      });
}

} // namespace

void triangulate_many(Device &device, std::size_t count,
                      const std::function<Input(std::size_t)> &input, const Options &options,
                      const Done &done) {
  validate(options); // the same for every input: an error here is the batch's
  mesh_on(device, count, input, options, done);
}

std::vector<BatchResult> triangulate_many(Device &device, const std::vector<Input> &inputs,
                                          const Options &options) {
  validate(options);
  std::vector<BatchResult> results(inputs.size());
  mesh_on(
      device, inputs.size(), [&](std::size_t i) -> const Input & { return inputs[i]; }, options,
      [&](std::size_t i, BatchResult &&result) { results[i] = std::move(result); });
  return results;
}

std::vector<BatchResult> triangulate_many(Device &device, const std::vector<Input> &inputs,
                                          const std::string &switches) {
  return triangulate_many(device, inputs, parse_switches(switches));
}

void triangulate_many(std::size_t count, const std::function<Input(std::size_t)> &input,
                      const Options &options,
                      const std::function<void(std::size_t, BatchResult &&)> &done) {
  validate(options);
  offer_pocl_drivers(options.device); // before OpenCL starts (device_choice.hpp)
  find_device(options.device);        // no such device: the batch's error
  // A pack runs on the device its first input would take, held meanwhile.
  const OnDevice on_device = [&](const Input &first, const std::function<void(Device &)> &work) {
    const std::shared_ptr<SharedDevice> shared = shared_device_for(first, options, Meshing::batch);
    const std::lock_guard<std::mutex> held(shared->busy);
    work(*shared->device);
  };
  // Input i's device is held until done() returns (the process keeps it).
  mesh_in_order(
      count, input, options, done,
      [&](const Done &in_order) { return Pack(options, in_order, on_device); },
      [&](const Input &given) {
        const std::shared_ptr<SharedDevice> shared =
            shared_device_for(given, options, Meshing::batch);
        return Target{shared->device.get(), &shared->busy, streams_on(*shared->device, options)};
      },
      [&](const Input &given, Device &on, std::mutex *busy, std::unique_lock<std::mutex> &held) {
        held = std::unique_lock<std::mutex>(*busy);
        return attempt(
            on, [&]() -> const Input & { return given; }, options);
      });
}

std::vector<BatchResult> triangulate_many(const std::vector<Input> &inputs,
                                          const Options &options) {
  std::vector<BatchResult> results(inputs.size());
  triangulate_many(
      inputs.size(), [&](std::size_t i) { return inputs[i]; }, options,
      [&](std::size_t i, BatchResult &&result) { results[i] = std::move(result); });
  return results;
}

} // namespace clmesh
