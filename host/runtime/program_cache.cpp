#include "runtime/program_cache.hpp"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <system_error>
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

// 64-bit FNV-1a from `basis`; two bases give the 128-bit file name.
std::uint64_t fnv1a(const std::string &text, std::uint64_t basis) {
  std::uint64_t hash = basis;
  for (const unsigned char c : text) {
    hash ^= c;
    hash *= 0x100000001b3ull;
  }
  return hash;
}

} // namespace

ProgramCache::ProgramCache(const std::string &source, const std::string &identity) {
  const std::string dir = cache_directory();
  if (dir.empty())
    return;
  // Lengths first, so that no two (identity, source) pairs give one text.
  const std::string key = std::to_string(identity.size()) + ":" + identity + "\n" +
                          std::to_string(source.size()) + ":" + source;
  char name[40];
  std::snprintf(name, sizeof name, "%016llx%016llx",
                static_cast<unsigned long long>(fnv1a(key, 0xcbf29ce484222325ull)),
                static_cast<unsigned long long>(fnv1a(key, 0x84222325cbf29ce4ull)));
  path_ = dir + "/" + name + ".bin";
}

std::optional<std::vector<unsigned char>> ProgramCache::load() const {
  if (path_.empty())
    return std::nullopt;
  std::ifstream in(path_, std::ios::binary | std::ios::ate);
  if (!in)
    return std::nullopt;
  const std::streamoff size = in.tellg();
  if (size <= 0)
    return std::nullopt;
  std::vector<unsigned char> binary(static_cast<std::size_t>(size));
  in.seekg(0);
  if (!in.read(reinterpret_cast<char *>(binary.data()), size))
    return std::nullopt;
  return binary;
}

void ProgramCache::store(const std::vector<unsigned char> &binary) const {
  if (path_.empty() || binary.empty())
    return;
  std::error_code error;
  std::filesystem::create_directories(std::filesystem::path(path_).parent_path(), error);
  if (error)
    return;
  // Written aside, then renamed: a reader never sees half a file.
  const std::string partial = path_ + "." + std::to_string(getpid()) + ".partial";
  {
    std::ofstream out(partial, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char *>(binary.data()),
              static_cast<std::streamsize>(binary.size()));
    if (!out) {
      out.close();
      std::filesystem::remove(partial, error);
      return;
    }
  }
  std::filesystem::rename(partial, path_, error);
  if (error)
    std::filesystem::remove(partial, error);
}

} // namespace clmesh
