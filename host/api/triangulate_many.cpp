// clmesh — many inputs, one device: triangulate() on each, every input's
// error kept in its own result instead of ending the batch.
#include "api/shared_device.hpp"
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
  const std::shared_ptr<SharedDevice> shared = shared_device(options.device);
  std::lock_guard<std::mutex> lock(shared->busy);
  triangulate_many(*shared->device, count, input, options, done);
}

std::vector<BatchResult> triangulate_many(const std::vector<Input> &inputs,
                                          const Options &options) {
  validate(options);
  const std::shared_ptr<SharedDevice> shared = shared_device(options.device);
  std::lock_guard<std::mutex> lock(shared->busy);
  return triangulate_many(*shared->device, inputs, options);
}

} // namespace clmesh
