// clmesh — typed errors. Library code never exits; it throws one of these.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

namespace clmesh {

// `text` as a message can show it: control bytes (NUL, ESC, newline, DEL, the
// C1 controls) and bytes that are not UTF-8 become \xHH, so that no byte of
// an input file or argument acts on the terminal, cuts a C string short or
// breaks the message's line; everything else is kept. printable() of its own
// output changes nothing.
std::string printable(std::string_view text);

// printable(text) between single quotes, as every message quotes input text
// (tokens, switches, file names); beyond 256 bytes it is cut, "..." after it.
std::string quote(std::string_view text);

// Base of every error clmesh throws.
class Error : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

// Malformed or unusable input: names the file and (when known) the line.
class InputError : public Error {
public:
  InputError(std::string file, long line, const std::string &problem)
      : Error(format(file, line, problem)), file_(std::move(file)), line_(line), problem_(problem) {
  }
  const std::string &file() const { return file_; }
  long line() const { return line_; } // 0 when the problem is not on one line
  const std::string &problem() const { return problem_; }

private:
  static std::string format(const std::string &file, long line, const std::string &problem) {
    const std::string where = printable(file);
    return line > 0 ? where + ":" + std::to_string(line) + ": " + problem : where + ": " + problem;
  }
  std::string file_;
  long line_;
  std::string problem_;
};

// Switches or option values that are unknown, malformed, out of range or do
// not go together.
class OptionError : public Error {
public:
  using Error::Error;
};

// No usable OpenCL device, or a device without what clmesh needs.
class DeviceError : public Error {
public:
  using Error::Error;
};

// An OpenCL call failed: carries the symbolic code name, the phase and the kernel.
class OpenCLError : public Error {
public:
  OpenCLError(int code, const std::string &what_failed, const std::string &phase,
              const std::string &kernel);
  int code() const { return code_; }

private:
  int code_;
};

// The algorithm met a state it cannot handle (a bug, reported rather than hidden).
class InternalError : public Error {
public:
  using Error::Error;
};

// Symbolic name of an OpenCL status code, e.g. "CL_OUT_OF_RESOURCES".
const char *opencl_error_name(int code);

} // namespace clmesh
