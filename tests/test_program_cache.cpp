// The on-disk cache of built programs (host/program_cache.hpp): entries keyed
// by everything a binary depends on, a device that builds from its entry, and
// a damaged entry that falls back to the source.
#include <doctest/doctest.h>

#include "clmesh/device.hpp"
#include "runtime/opencl_context.hpp"
#include "runtime/program_cache.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;

namespace {

// CLMESH_CACHE_DIR set to `value` (nullopt: unset) while it lives.
class CacheDirectory {
public:
  explicit CacheDirectory(const std::optional<std::string> &value) {
    if (const char *old = std::getenv("CLMESH_CACHE_DIR"))
      old_ = old;
    if (value)
      setenv("CLMESH_CACHE_DIR", value->c_str(), 1);
    else
      unsetenv("CLMESH_CACHE_DIR");
  }
  ~CacheDirectory() {
    if (old_)
      setenv("CLMESH_CACHE_DIR", old_->c_str(), 1);
    else
      unsetenv("CLMESH_CACHE_DIR");
  }

private:
  std::optional<std::string> old_;
};

fs::path fresh_directory(const std::string &name) {
  const fs::path dir =
      fs::temp_directory_path() / ("clmesh-" + name + "-" + std::to_string(getpid()));
  fs::remove_all(dir);
  return dir;
}

std::vector<fs::path> entries(const fs::path &dir) {
  std::vector<fs::path> found;
  if (fs::exists(dir))
    for (const auto &entry : fs::directory_iterator(dir))
      found.push_back(entry.path());
  return found;
}

std::string contents(const fs::path &file) {
  std::ifstream in(file, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

} // namespace

TEST_CASE("program cache: entries are keyed by source and identity; empty turns it off") {
  const fs::path dir = fresh_directory("cache-keys");
  {
    const CacheDirectory set(dir.string());
    const clmesh::ProgramCache cache("source", "identity");
    CHECK_FALSE(cache.load().has_value());
    cache.store({1, 2, 3});
    const auto loaded = clmesh::ProgramCache("source", "identity").load();
    REQUIRE(loaded.has_value());
    CHECK(*loaded == std::vector<unsigned char>{1, 2, 3});
    CHECK_FALSE(clmesh::ProgramCache("source.", "identity").load().has_value());
    CHECK_FALSE(clmesh::ProgramCache("source", "identity.").load().has_value());
    // The length prefixes keep the boundary between the two parts.
    CHECK_FALSE(clmesh::ProgramCache("esource", "identit").load().has_value());
    CHECK(entries(dir).size() == 1u); // no partial file left behind
  }
  {
    const CacheDirectory off(std::string{});
    const clmesh::ProgramCache cache("other source", "identity");
    cache.store({4, 5});
    CHECK_FALSE(cache.load().has_value());
    CHECK(entries(dir).size() == 1u);
  }
  fs::remove_all(dir);
}

TEST_CASE("program cache: a device builds from its entry, from the source when it is damaged") {
  const fs::path dir = fresh_directory("cache-device");
  const CacheDirectory set(dir.string());
  {
    auto device = clmesh::open_device();
    CHECK_FALSE(device->program("scan.cl", "test").getInfo<CL_PROGRAM_SOURCE>().empty());
  }
  const auto stored = entries(dir);
  REQUIRE(stored.size() == 1u);
  const std::string binary = contents(stored.front());
  CHECK(binary.size() > 0u);
  {
    auto device = clmesh::open_device(); // built from the binary: no source
    CHECK(device->program("scan.cl", "test").getInfo<CL_PROGRAM_SOURCE>().empty());
    CHECK_NOTHROW(device->kernel("scan.cl", "scan_blocks", "test"));
  }
  {
    std::ofstream damage(stored.front(), std::ios::binary | std::ios::trunc);
    damage << "not a program binary";
  }
  {
    auto device = clmesh::open_device(); // the damaged entry is built again from the source
    CHECK_FALSE(device->program("scan.cl", "test").getInfo<CL_PROGRAM_SOURCE>().empty());
    CHECK_NOTHROW(device->kernel("scan.cl", "scan_blocks", "test"));
  }
  CHECK(contents(stored.front()) != "not a program binary"); // stored again
  fs::remove_all(dir);
}
