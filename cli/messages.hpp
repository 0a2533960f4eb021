// clmesh CLI — where messages go: straight to standard output and standard
// error, or, on a batch worker meshing an input, into that input's record,
// printed in input order once the inputs before it are done.
#pragma once

#include <string>
#include <vector>

namespace cli {

// An input's messages in the order they were said, each for standard
// output or standard error.
class Messages {
public:
  void add(bool error, std::string text);
  // Prints them, as say() and warn() would have.
  void replay() const;
  // As bytes (to pass between processes), and back.
  std::string pack() const;
  static Messages unpack(const std::string &bytes);

private:
  struct Chunk {
    bool error;
    std::string text;
  };
  std::vector<Chunk> chunks_;
};

// printf to standard output (say) or standard error (warn), or into the
// Messages this thread captures into.
[[gnu::format(printf, 1, 2)]] void say(const char *format, ...);
[[gnu::format(printf, 1, 2)]] void warn(const char *format, ...);
// Flushes standard output before a line on standard error (a no-op while
// capturing: the record keeps the order).
void flush_said();

// While alive, say() and warn() on this thread go into `messages`.
class Capture {
public:
  explicit Capture(Messages &messages);
  ~Capture();
  Capture(const Capture &) = delete;
  Capture &operator=(const Capture &) = delete;

private:
  Messages *previous_;
};

} // namespace cli
