// clmesh CLI — messages said straight or captured per input (messages.hpp).
#include "messages.hpp"

#include <cstdarg>
#include <cstdio>

namespace cli {
namespace {

thread_local Messages *captured = nullptr;

void emit(bool error, const char *format, std::va_list arguments) {
  FILE *stream = error ? stderr : stdout;
  if (!captured) {
    std::vfprintf(stream, format, arguments);
    return;
  }
  std::va_list copy;
  va_copy(copy, arguments);
  const int length = std::vsnprintf(nullptr, 0, format, copy);
  va_end(copy);
  if (length <= 0)
    return;
  std::string text(static_cast<std::size_t>(length) + 1, '\0');
  std::vsnprintf(&text[0], text.size(), format, arguments);
  text.pop_back();
  captured->add(error, std::move(text));
}

} // namespace

void Messages::add(bool error, std::string text) {
  if (!chunks_.empty() && chunks_.back().error == error)
    chunks_.back().text += text;
  else
    chunks_.push_back({error, std::move(text)});
}

void Messages::replay() const {
  for (const Chunk &chunk : chunks_) {
    if (chunk.error)
      std::fflush(stdout);
    std::fputs(chunk.text.c_str(), chunk.error ? stderr : stdout);
  }
}

// Each chunk: its stream ('o' or 'e'), its length in decimal, ':', its text.
std::string Messages::pack() const {
  std::string bytes;
  for (const Chunk &chunk : chunks_)
    bytes += (chunk.error ? "e" : "o") + std::to_string(chunk.text.size()) + ":" + chunk.text;
  return bytes;
}

Messages Messages::unpack(const std::string &bytes) {
  Messages messages;
  std::size_t at = 0;
  while (at < bytes.size()) {
    const std::size_t colon = bytes.find(':', at);
    if (colon == std::string::npos)
      break;
    const std::size_t length = std::stoul(bytes.substr(at + 1, colon - at - 1));
    messages.add(bytes[at] == 'e', bytes.substr(colon + 1, length));
    at = colon + 1 + length;
  }
  return messages;
}

void say(const char *format, ...) {
  std::va_list arguments;
  va_start(arguments, format);
  emit(false, format, arguments);
  va_end(arguments);
}

void warn(const char *format, ...) {
  std::va_list arguments;
  va_start(arguments, format);
  emit(true, format, arguments);
  va_end(arguments);
}

void flush_said() {
  if (!captured)
    std::fflush(stdout);
}

Capture::Capture(Messages &messages) : previous_(captured) { captured = &messages; }

Capture::~Capture() { captured = previous_; }

} // namespace cli
