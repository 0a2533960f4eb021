// clmesh CLI — a batch meshed by worker processes (worker_processes.hpp).
#include "worker_processes.hpp"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <optional>
#include <poll.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <system_error>
#include <thread>
#include <unistd.h>

namespace cli {
namespace {

constexpr std::size_t kNone = static_cast<std::size_t>(-1);
// The input field of a record that is not an input's: the worker's start
// failed, or it retired.
constexpr long kStartFailed = -1;
constexpr long kRetired = -2;

// The memory the parent and its workers share: the next input to take, the
// inputs written, and the input each stream of each worker slot holds.
class Shared {
public:
  Shared(std::size_t inputs, unsigned workers)
      : slots_(workers * kMostStreams), bytes_(sizeof(std::atomic<std::size_t>) * (1 + slots_) +
                                               sizeof(std::atomic<unsigned char>) * inputs) {
    memory_ = ::mmap(nullptr, bytes_, PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
    if (memory_ == MAP_FAILED)
      throw std::system_error(errno, std::generic_category(), "mmap");
    auto *sizes = static_cast<std::atomic<std::size_t> *>(memory_);
    next_ = new (sizes) std::atomic<std::size_t>(0);
    for (unsigned slot = 0; slot < slots_; ++slot)
      new (sizes + 1 + slot) std::atomic<std::size_t>(kNone);
    holding_ = sizes + 1;
    written_ = reinterpret_cast<std::atomic<unsigned char> *>(sizes + 1 + slots_);
    for (std::size_t i = 0; i < inputs; ++i)
      new (written_ + i) std::atomic<unsigned char>(0);
  }
  ~Shared() { ::munmap(memory_, bytes_); }
  Shared(const Shared &) = delete;
  Shared &operator=(const Shared &) = delete;

  std::atomic<std::size_t> &next() { return *next_; }
  // The input that stream `stream` of worker `slot` holds (kNone: none).
  std::atomic<std::size_t> &holding(unsigned slot, unsigned stream) {
    return holding_[slot * kMostStreams + stream];
  }
  std::atomic<unsigned char> &written(std::size_t input) { return written_[input]; }

private:
  unsigned slots_;
  std::size_t bytes_;
  void *memory_;
  std::atomic<std::size_t> *next_, *holding_;
  std::atomic<unsigned char> *written_;
};

// A record on a worker's pipe: "input status length\n" then the packed
// messages; input kStartFailed or kRetired: the worker's start.
void send(int fd, long input, int status, const Messages &messages) {
  const std::string body = messages.pack();
  std::string record = std::to_string(input) + " " + std::to_string(status) + " " +
                       std::to_string(body.size()) + "\n" + body;
  const char *at = record.data();
  std::size_t left = record.size();
  while (left > 0) {
    const ssize_t wrote = ::write(fd, at, left);
    if (wrote < 0 && errno == EINTR)
      continue;
    if (wrote <= 0)
      ::_exit(1); // the parent is gone
    at += wrote;
    left -= static_cast<std::size_t>(wrote);
  }
}

// One stream of a worker: takes the next input no stream took, until none is
// left, and sends each one's record (one stream at a time).
void take_inputs(const WorkerBatch &batch, Shared &shared, unsigned slot, unsigned stream, int fd,
                 std::mutex &sending) {
  for (;;) {
    const std::size_t i = shared.next().fetch_add(1);
    if (i >= batch.count)
      break;
    shared.holding(slot, stream) = i;
    const std::size_t before = batch.follows[i];
    while (before != kNone && !shared.written(before))
      ::usleep(1000);
    Messages messages;
    int status;
    {
      Capture capture(messages);
      status = batch.mesh(i, stream);
    }
    shared.written(i) = 1;
    {
      const std::lock_guard<std::mutex> lock(sending);
      send(fd, static_cast<long>(i), status, messages);
    }
    shared.holding(slot, stream) = kNone;
  }
}

[[noreturn]] void work(const WorkerBatch &batch, Shared &shared, unsigned slot, int fd) {
  {
    Messages messages;
    WorkerStart start;
    {
      Capture capture(messages);
      start = batch.start(slot);
    }
    if (start != WorkerStart::mesh) {
      send(fd, start == WorkerStart::retire ? kRetired : kStartFailed, 1, messages);
      ::_exit(0);
    }
  }
  const unsigned streams = batch.streams ? std::clamp(batch.streams(), 1u, kMostStreams) : 1u;
  std::mutex sending;
  std::vector<std::thread> threads;
  for (unsigned stream = 1; stream < streams; ++stream)
    threads.emplace_back(take_inputs, std::cref(batch), std::ref(shared), slot, stream, fd,
                         std::ref(sending));
  take_inputs(batch, shared, slot, 0, fd, sending);
  for (std::thread &thread : threads)
    thread.join();
  std::fflush(nullptr);
  ::_exit(0);
}

struct Worker {
  pid_t pid = -1;
  int fd = -1;
  std::string received;
  bool retired = false;
};

Worker start_worker(const WorkerBatch &batch, Shared &shared, unsigned slot,
                    const std::vector<Worker> &others) {
  int pipe_ends[2];
  if (::pipe(pipe_ends) != 0)
    throw std::system_error(errno, std::generic_category(), "pipe");
  std::fflush(nullptr); // nothing buffered is printed twice
  const pid_t pid = ::fork();
  if (pid < 0)
    throw std::system_error(errno, std::generic_category(), "fork");
  if (pid == 0) {
    ::close(pipe_ends[0]);
    for (const Worker &other : others)
      if (other.fd >= 0)
        ::close(other.fd);
    work(batch, shared, slot, pipe_ends[1]);
  }
  ::close(pipe_ends[1]);
  Worker worker;
  worker.pid = pid;
  worker.fd = pipe_ends[0];
  return worker;
}

std::string death(int status) {
  if (WIFSIGNALED(status))
    return std::string("signal ") + std::to_string(WTERMSIG(status)) + ", " +
           strsignal(WTERMSIG(status));
  return "exit status " + std::to_string(WEXITSTATUS(status));
}

} // namespace

WorkerOutcome run_worker_processes(const WorkerBatch &batch) {
  struct Result {
    int status;
    Messages messages;
  };
  Shared shared(batch.count, batch.workers);
  std::vector<Worker> workers;
  for (unsigned slot = 0; slot < batch.workers; ++slot)
    workers.push_back(start_worker(batch, shared, slot, workers));
  std::vector<std::optional<Result>> results(batch.count);
  std::size_t handed_on = 0;
  std::optional<Messages> failed_start;
  auto stop_all = [&]() {
    for (Worker &worker : workers)
      if (worker.pid > 0) {
        ::kill(worker.pid, SIGTERM);
        ::waitpid(worker.pid, nullptr, 0);
        worker.pid = -1;
      }
  };
  // Takes the whole records that `worker` sent.
  auto take_records = [&](Worker &worker) {
    for (;;) {
      const std::size_t end = worker.received.find('\n');
      if (end == std::string::npos)
        return;
      long input = 0, length = 0;
      int status = 0;
      if (std::sscanf(worker.received.c_str(), "%ld %d %ld", &input, &status, &length) != 3 ||
          worker.received.size() < end + 1 + static_cast<std::size_t>(length))
        return;
      Messages messages = Messages::unpack(worker.received.substr(end + 1, length));
      worker.received.erase(0, end + 1 + length);
      if (input == kRetired)
        worker.retired = true;
      else if (input < 0)
        failed_start = std::move(messages);
      else
        results[input] = Result{status, std::move(messages)};
    }
  };
  while (handed_on < batch.count && !failed_start) {
    bool alive = false;
    for (const Worker &worker : workers)
      alive = alive || worker.fd >= 0;
    if (!alive) { // a worker died before it marked the input it took
      for (std::size_t i = handed_on; i < batch.count; ++i)
        if (!results[i]) {
          Messages messages;
          {
            Capture capture(messages);
            warn("clmesh: %s: its worker process died before meshing it\n", batch.name(i).c_str());
          }
          results[i] = Result{1, std::move(messages)};
        }
    }
    std::vector<pollfd> polled;
    for (const Worker &worker : workers)
      polled.push_back({worker.fd, POLLIN, 0});
    if (alive && ::poll(polled.data(), polled.size(), -1) < 0) {
      if (errno == EINTR)
        continue;
      throw std::system_error(errno, std::generic_category(), "poll");
    }
    for (unsigned slot = 0; slot < workers.size(); ++slot) {
      Worker &worker = workers[slot];
      if (worker.fd < 0 || polled[slot].revents == 0)
        continue;
      char buffer[65536];
      const ssize_t got = ::read(worker.fd, buffer, sizeof buffer);
      if (got < 0 && errno == EINTR)
        continue;
      if (got > 0) {
        worker.received.append(buffer, static_cast<std::size_t>(got));
        take_records(worker);
        continue;
      }
      // The worker is done, or died.
      ::close(worker.fd);
      worker.fd = -1;
      int status = 0;
      ::waitpid(worker.pid, &status, 0);
      worker.pid = -1;
      for (unsigned stream = 0; stream < kMostStreams; ++stream) {
        const std::size_t held = shared.holding(slot, stream);
        if (held == kNone || results[held])
          continue;
        Messages messages;
        {
          Capture capture(messages);
          warn("clmesh: %s: the worker process meshing it died (%s)\n", batch.name(held).c_str(),
               death(status).c_str());
        }
        results[held] = Result{1, std::move(messages)};
        shared.holding(slot, stream) = kNone;
        shared.written(held) = 1;
      }
      if (shared.next() < batch.count && !worker.retired)
        worker = start_worker(batch, shared, slot, workers);
    }
    while (handed_on < batch.count && results[handed_on]) {
      batch.done(handed_on, results[handed_on]->status, results[handed_on]->messages);
      results[handed_on].reset();
      ++handed_on;
    }
  }
  WorkerOutcome outcome;
  for (const Worker &worker : workers)
    outcome.worked += !worker.retired;
  if (failed_start) {
    stop_all();
    failed_start->replay();
    outcome.status = 1;
    return outcome;
  }
  for (Worker &worker : workers)
    if (worker.pid > 0) {
      ::waitpid(worker.pid, nullptr, 0);
      ::close(worker.fd);
    }
  return outcome;
}

} // namespace cli
