// clmesh CLI — a batch meshed by several worker processes at once.
//
// Each worker is a process of its own, forked before the parent makes any
// OpenCL call, with its own devices (OpenCL implementations share state
// between the devices of one process: PoCL's cache of built kernels is not
// safe for two of its CPU devices running at once). A worker takes the next
// input that no worker took (a counter in shared memory), meshes it with its
// messages captured, and sends its exit status and messages to the parent,
// which hands them on in input order. An input whose outputs have the names
// of an earlier input's waits until that one is written, so that the later
// files are left, as when meshed in turn. A worker that dies fails the input
// it held (the message names the signal) and a new worker takes its place.
// A worker may also retire at its start, before taking an input (one device
// that the processes would only share by time slices): it is not replaced.
// A worker may mesh several inputs at once, each on a thread (a stream) of
// its own: on a GPU, where the launches of one context's queues overlap.
#pragma once

#include "messages.hpp"

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace cli {

// What a worker does after its start.
enum class WorkerStart {
  mesh,   // take inputs
  retire, // take none, and leave the inputs to the other workers
  failed, // the run fails (the start said why)
};

// The most streams a worker may run.
constexpr unsigned kMostStreams = 64;

struct WorkerBatch {
  std::size_t count = 0; // inputs 0 .. count-1
  unsigned workers = 2;
  // For each input, an earlier input with the same output names (the
  // nearest), or npos.
  std::vector<std::size_t> follows;
  // In each worker (slot 0 .. workers-1) before its first input. Slot 0
  // must not retire: some worker has to mesh the inputs.
  std::function<WorkerStart(unsigned slot)> start;
  // In a worker after its start: how many inputs it meshes at once, each
  // on a thread of its own (1 to kMostStreams; none: 1).
  std::function<unsigned()> streams;
  // In a worker, on stream 0 .. streams - 1: meshes input i and returns its
  // exit status; says and warns into the captured messages. Called from
  // several threads at once when streams() > 1.
  std::function<int(std::size_t, unsigned stream)> mesh;
  // In the parent, in input order: input i's exit status and messages.
  std::function<void(std::size_t, int, const Messages &)> done;
  // The input's name, for the message when its worker dies.
  std::function<std::string(std::size_t)> name;
};

struct WorkerOutcome {
  int status = 0;      // 1 when a worker's start failed (its messages
                       // printed, the other workers stopped)
  unsigned worked = 0; // the worker slots that did not retire
};

// Runs the batch.
WorkerOutcome run_worker_processes(const WorkerBatch &batch);

} // namespace cli
