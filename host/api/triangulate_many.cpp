// clmesh — many inputs, one device: triangulate() on each, every input's
// error kept in its own result instead of ending the batch.
#include "api/device_choice.hpp"
#include "api/shared_device.hpp"
#include "clmesh/device.hpp"
#include "clmesh/errors.hpp"
#include "clmesh/triangulate.hpp"

#include <memory>
#include <mutex>
#include <utility>

namespace clmesh {

namespace {

// The mesh of the input `input_of()` gives, or the error that stopped it.
template <class InputOf>
BatchResult attempt(Device &device, const InputOf &input_of, const Options &options) {
  BatchResult result;
  try {
    result.mesh = triangulate(device, input_of(), options);
  } catch (const std::exception &error) {
    result.error = std::current_exception();
    result.message = error.what();
  }
  return result;
}

} // namespace

void triangulate_many(Device &device, std::size_t count,
                      const std::function<Input(std::size_t)> &input, const Options &options,
                      const std::function<void(std::size_t, BatchResult &&)> &done) {
  validate(options); // the same for every input: an error here is the batch's
  for (std::size_t i = 0; i < count; ++i)
    done(i, attempt(
                device, [&] { return input(i); }, options));
}

std::vector<BatchResult> triangulate_many(Device &device, const std::vector<Input> &inputs,
                                          const Options &options) {
  validate(options);
  std::vector<BatchResult> results;
  results.reserve(inputs.size());
  for (const Input &input : inputs)
    results.push_back(attempt(
        device, [&]() -> const Input & { return input; }, options));
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
  for (std::size_t i = 0; i < count; ++i) {
    BatchResult result;
    std::unique_lock<std::mutex> held; // input i's device (the process keeps it)
    try {
      const Input given = input(i);
      const std::shared_ptr<SharedDevice> shared = shared_device_for(given, options);
      held = std::unique_lock<std::mutex>(shared->busy);
      result = attempt(
          *shared->device, [&]() -> const Input & { return given; }, options);
    } catch (const std::exception &error) { // from input(i) or the device's opening
      result.error = std::current_exception();
      result.message = error.what();
    }
    done(i, std::move(result)); // the device still held
  }
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
