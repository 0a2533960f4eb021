#include "runtime/program_cache.hpp"

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <random>
#include <system_error>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace clmesh {

namespace {

std::string cache_directory() {
  if (const char *dir = std::getenv("CLMESH_CACHE_DIR"))
    return dir; // empty: off
  if (const char *xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
    return std::string(xdg) + "/clmesh";
  if (const char *home = std::getenv("HOME"); home && *home)
    return std::string(home) + "/.cache/clmesh";
  return "";
}

constexpr std::uint64_t fnv_basis = 0xcbf29ce484222325ull;

// 64-bit FNV-1a of `size` bytes from `hash` (a basis, or the hash so far).
std::uint64_t fnv1a(const void *data, std::size_t size, std::uint64_t hash) {
  const auto *bytes = static_cast<const unsigned char *>(data);
  for (std::size_t i = 0; i < size; ++i) {
    hash ^= bytes[i];
    hash *= 0x100000001b3ull;
  }
  return hash;
}

// Little-endian fields of `bytes` bytes.
void put(unsigned char *out, std::uint64_t value, int bytes) {
  for (int i = 0; i < bytes; ++i)
    out[i] = static_cast<unsigned char>(value >> (8 * i));
}

std::uint64_t get(const unsigned char *in, int bytes) {
  std::uint64_t value = 0;
  for (int i = 0; i < bytes; ++i)
    value |= static_cast<std::uint64_t>(in[i]) << (8 * i);
  return value;
}

// The payload's checksum: FNV-1a 64 over little-endian 8-byte words, then
// over the bytes left. A word at a time costs an eighth of the byte-wise
// hash on a megabyte binary read on every run; a change to any one word still
// changes the result (each step maps the running hash one to one).
std::uint64_t checksum(const unsigned char *data, std::size_t size) {
  std::uint64_t hash = fnv_basis;
  std::size_t i = 0;
  for (; i + 8 <= size; i += 8) {
    hash ^= get(data + i, 8);
    hash *= 0x100000001b3ull;
  }
  return fnv1a(data + i, size - i, hash);
}

// An entry: a header of fixed size, then the driver's binary (the payload).
// Every field little-endian:
//   0  magic "clmeshPB"        8 bytes
//   8  format version          u32
//  12  header size             u32
//  16  key (both halves)       2 x u64
//  32  payload size            u64
//  40  checksum of payload    u64 (checksum() above)
constexpr char magic[8] = {'c', 'l', 'm', 'e', 's', 'h', 'P', 'B'};
constexpr std::uint32_t format_version = 1;
constexpr std::size_t header_size = 48;

// Closes a file descriptor when it goes.
class File {
public:
  explicit File(int fd) : fd_(fd) {}
  File(const File &) = delete;
  File &operator=(const File &) = delete;
  ~File() {
    if (fd_ >= 0)
      ::close(fd_);
  }
  int fd() const { return fd_; }
  // Closes now: false when the close reports an error (a write it lost).
  bool close() {
    const int fd = fd_;
    fd_ = -1;
    return ::close(fd) == 0;
  }

private:
  int fd_;
};

bool read_all(int fd, unsigned char *data, std::size_t size) {
  while (size > 0) {
    const ssize_t got = ::read(fd, data, size);
    if (got < 0 && errno == EINTR)
      continue;
    if (got <= 0)
      return false; // an error, or the file ended early
    data += got;
    size -= static_cast<std::size_t>(got);
  }
  return true;
}

bool write_all(int fd, const unsigned char *data, std::size_t size) {
  while (size > 0) {
    const ssize_t put = ::write(fd, data, size);
    if (put < 0 && errno == EINTR)
      continue;
    if (put <= 0)
      return false;
    data += put;
    size -= static_cast<std::size_t>(put);
  }
  return true;
}

// A suffix no other writer picks: another process has another pid, another
// thread another count, and the random part covers pids shared across
// containers that share the folder.
std::string unique_suffix() {
  static std::atomic<unsigned> count{0};
  std::uint64_t noise =
      static_cast<std::uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count());
  try {
    std::random_device device;
    noise ^= (static_cast<std::uint64_t>(device()) << 32) ^ device();
  } catch (const std::exception &) {
    // No random device: the clock and the count still differ between writers.
  }
  char suffix[64];
  std::snprintf(suffix, sizeof suffix, ".%ld-%u-%016llx.partial", static_cast<long>(getpid()),
                count.fetch_add(1), static_cast<unsigned long long>(noise));
  return suffix;
}

// Removes the partial files in `folder` that writers killed before their
// rename left behind: those older than an hour (a live writer takes well
// under a second).
void remove_stale_partials(const std::filesystem::path &folder) {
  namespace fs = std::filesystem;
  std::error_code error;
  const auto now = fs::file_time_type::clock::now();
  for (fs::directory_iterator it(folder, error), end; !error && it != end; it.increment(error)) {
    const std::string name = it->path().filename().string();
    const std::string suffix = ".partial";
    if (name.size() <= suffix.size() ||
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0 ||
        name.find(".bin.") == std::string::npos)
      continue;
    std::error_code ignored;
    const auto written = fs::last_write_time(it->path(), ignored);
    if (!ignored && now - written > std::chrono::hours(1))
      fs::remove(it->path(), ignored);
  }
}

} // namespace

ProgramCache::ProgramCache(const std::string &source, const std::string &identity) {
  const std::string dir = cache_directory();
  if (dir.empty())
    return;
  // Lengths first, so that no two (identity, source) pairs give one text.
  const std::string key = std::to_string(identity.size()) + ":" + identity + "\n" +
                          std::to_string(source.size()) + ":" + source;
  // Two bases give 128 bits.
  key_[0] = fnv1a(key.data(), key.size(), fnv_basis);
  key_[1] = fnv1a(key.data(), key.size(), 0x84222325cbf29ce4ull);
  char name[40];
  std::snprintf(name, sizeof name, "%016llx%016llx", static_cast<unsigned long long>(key_[0]),
                static_cast<unsigned long long>(key_[1]));
  path_ = dir + "/" + name + ".bin";
}

std::optional<std::vector<unsigned char>> ProgramCache::load() const noexcept {
  if (path_.empty())
    return std::nullopt;
  try {
    // Non-blocking: a FIFO at the entry's name must not hang the run.
    File file(::open(path_.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK));
    if (file.fd() < 0)
      return std::nullopt;
    struct stat info {};
    if (::fstat(file.fd(), &info) != 0 || !S_ISREG(info.st_mode) ||
        info.st_size < static_cast<off_t>(header_size))
      return std::nullopt;
    unsigned char header[header_size];
    if (!read_all(file.fd(), header, header_size))
      return std::nullopt;
    const std::uint64_t payload_size = get(header + 32, 8);
    if (std::memcmp(header, magic, sizeof magic) != 0 || get(header + 8, 4) != format_version ||
        get(header + 12, 4) != header_size || get(header + 16, 8) != key_[0] ||
        get(header + 24, 8) != key_[1] || payload_size == 0 ||
        payload_size != static_cast<std::uint64_t>(info.st_size) - header_size)
      return std::nullopt;
    std::vector<unsigned char> binary(static_cast<std::size_t>(payload_size));
    if (!read_all(file.fd(), binary.data(), binary.size()) ||
        checksum(binary.data(), binary.size()) != get(header + 40, 8))
      return std::nullopt;
    return binary;
  } catch (const std::exception &) {
    return std::nullopt; // out of memory: no entry
  }
}

void ProgramCache::store(const std::vector<unsigned char> &binary) const noexcept {
  if (path_.empty() || binary.empty())
    return;
  try {
    namespace fs = std::filesystem;
    const fs::path entry(path_);
    std::error_code error;
    fs::create_directories(entry.parent_path(), error);
    if (error && !fs::is_directory(entry.parent_path(), error))
      return;
    unsigned char header[header_size] = {};
    std::memcpy(header, magic, sizeof magic);
    put(header + 8, format_version, 4);
    put(header + 12, header_size, 4);
    put(header + 16, key_[0], 8);
    put(header + 24, key_[1], 8);
    put(header + 32, binary.size(), 8);
    put(header + 40, checksum(binary.data(), binary.size()), 8);
    // Written aside under a name of its own, then renamed over the entry: a
    // reader sees the old entry or the whole new one, and writers filling the
    // same entry at once each rename a whole file. No fsync: an entry that a
    // crash leaves short fails its checks and is written again.
    const std::string partial = path_ + unique_suffix();
    File file(::open(partial.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666));
    if (file.fd() < 0)
      return;
    const bool written = write_all(file.fd(), header, header_size) &&
                         write_all(file.fd(), binary.data(), binary.size());
    if (!file.close() || !written) {
      ::unlink(partial.c_str());
      return;
    }
    if (::rename(partial.c_str(), path_.c_str()) != 0) {
      // A directory (or another thing rename does not replace) holds the
      // name: an empty one goes, then one more try.
      fs::remove(entry, error);
      if (::rename(partial.c_str(), path_.c_str()) != 0)
        ::unlink(partial.c_str());
    }
    remove_stale_partials(entry.parent_path());
  } catch (const std::exception &) {
    // Out of memory: no entry this time.
  }
}

} // namespace clmesh
