// The on-disk cache of built programs (host/runtime/program_cache.hpp):
// entries keyed by everything a binary depends on, a device that builds from
// its entry, and a damaged entry, a cache folder that cannot be used or
// writers at once: the run builds from the source and the entry is whole again.
#include <doctest/doctest.h>

#include "clmesh/device.hpp"
#include "runtime/opencl_context.hpp"
#include "runtime/program_cache.hpp"
#include "test_support.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <sys/stat.h>
#include <thread>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;

namespace {

// CLMESH_CACHE_DIR set to `value` (nullopt: unset) while it lives. The
// device's check of its predicates is off meanwhile: the folder holds the
// entries of the programs a test builds, and no other.
class CacheDirectory {
public:
  explicit CacheDirectory(const std::optional<std::string> &value)
      : directory_("CLMESH_CACHE_DIR", value), check_("CLMESH_PREDICATE_CHECK", "off") {}

private:
  test_support::Environment directory_, check_;
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

void write_file(const fs::path &file, const std::string &text) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out << text;
}

// Builds scan.cl on a fresh device (the cache is read again) and makes one of
// its kernels; true when the program came from the source, false when it
// came from a cache entry.
bool scan_built_from_source() {
  auto device = clmesh::open_device();
  const bool from_source = !device->program("scan.cl", "test").getInfo<CL_PROGRAM_SOURCE>().empty();
  CHECK_NOTHROW(device->kernel("scan.cl", "scan_blocks", "test"));
  return from_source;
}

// The one entry a first build of scan.cl leaves in the (empty) cache folder.
fs::path scan_entry(const fs::path &dir) {
  REQUIRE(scan_built_from_source());
  const auto stored = entries(dir);
  REQUIRE(stored.size() == 1u);
  return stored.front();
}

// `damage` applied to scan.cl's entry: the next build is from the source and
// does not fail, the entry is then whole again (the build after is from it).
template <typename Damage>
void damaged_scan_entry_is_rebuilt(const std::string &name, Damage damage) {
  const fs::path dir = fresh_directory(name);
  const CacheDirectory set(dir.string());
  const fs::path entry = scan_entry(dir);
  const std::string whole = contents(entry);
  damage(entry, whole);
  CHECK(scan_built_from_source());
  CHECK(fs::is_regular_file(entry)); // stored again
  CHECK_FALSE(scan_built_from_source());
  CHECK(entries(dir).size() == 1u); // no partial file left behind
  fs::remove_all(dir);
}

} // namespace

TEST_CASE("program cache: entries are keyed by source and identity, empty turns it off") {
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

TEST_CASE("program cache: a truncated entry is built again from the source, not handed to the "
          "driver") {
  // PoCL asserts (aborting the process) or crashes on a truncated binary.
  for (const double kept : {0.0001, 0.5, 0.9999})
    damaged_scan_entry_is_rebuilt("cache-truncated", [&](const fs::path &entry,
                                                         const std::string &whole) {
      fs::resize_file(entry, static_cast<std::uintmax_t>(static_cast<double>(whole.size()) * kept));
    });
  damaged_scan_entry_is_rebuilt("cache-truncated",
                                [](const fs::path &entry, const std::string &whole) {
                                  fs::resize_file(entry, whole.size() - 1);
                                });
}

TEST_CASE("program cache: an empty entry is built again from the source") {
  damaged_scan_entry_is_rebuilt(
      "cache-empty", [](const fs::path &entry, const std::string &) { write_file(entry, ""); });
}

TEST_CASE("program cache: a garbage entry is built again from the source") {
  SUBCASE("text") {
    damaged_scan_entry_is_rebuilt("cache-garbage", [](const fs::path &entry, const std::string &) {
      write_file(entry, "not a program binary");
    });
  }
  SUBCASE("bytes changed inside, size kept") {
    damaged_scan_entry_is_rebuilt(
        "cache-garbage", [](const fs::path &entry, const std::string &whole) {
          std::string damaged = whole;
          for (std::size_t i = damaged.size() / 3; i < damaged.size() / 3 + 4096; ++i)
            damaged[i] = static_cast<char>(damaged[i] ^ 0x5a);
          write_file(entry, damaged);
        });
  }
  SUBCASE("a byte appended") {
    damaged_scan_entry_is_rebuilt(
        "cache-garbage",
        [](const fs::path &entry, const std::string &whole) { write_file(entry, whole + "x"); });
  }
  SUBCASE("another program's entry") {
    // fill.cl's whole entry under scan.cl's name: built from it, the program
    // would lack scan.cl's kernels.
    damaged_scan_entry_is_rebuilt("cache-garbage", [](const fs::path &entry, const std::string &) {
      auto device = clmesh::open_device();
      device->program("fill.cl", "test");
      for (const auto &other : entries(entry.parent_path()))
        if (other != entry)
          fs::rename(other, entry);
    });
  }
}

TEST_CASE("program cache: an entry whose header checks out but that the driver refuses is "
          "built again from the source") {
  damaged_scan_entry_is_rebuilt(
      "cache-refused", [](const fs::path &entry, const std::string &whole) {
        // The entry's own header (magic, version, key) around a payload that is
        // no program binary, with its size and checksum (FNV-1a 64 over
        // little-endian 8-byte words; three whole words here).
        const std::string payload = "not a program binary....";
        std::uint64_t hash = 0xcbf29ce484222325ull;
        for (std::size_t word = 0; word < payload.size(); word += 8) {
          for (int i = 0; i < 8; ++i)
            hash ^= std::uint64_t{static_cast<unsigned char>(payload[word + i])} << (8 * i);
          hash *= 0x100000001b3ull;
        }
        std::string damaged = whole.substr(0, 32);
        for (const std::uint64_t field : {std::uint64_t{payload.size()}, hash})
          for (int i = 0; i < 8; ++i)
            damaged += static_cast<char>(field >> (8 * i));
        write_file(entry, damaged + payload);
      });
}

TEST_CASE("program cache: an entry's name taken by a directory") {
  const fs::path dir = fresh_directory("cache-directory");
  const CacheDirectory set(dir.string());
  const fs::path entry = scan_entry(dir);
  SUBCASE("an empty one is replaced") {
    fs::remove(entry);
    fs::create_directory(entry);
    CHECK(scan_built_from_source());
    CHECK(fs::is_regular_file(entry));
    CHECK_FALSE(scan_built_from_source());
  }
  SUBCASE("one with files is left alone") {
    fs::remove(entry);
    fs::create_directories(entry / "file");
    CHECK(scan_built_from_source());
    CHECK(scan_built_from_source());
    CHECK(fs::is_directory(entry / "file"));
    CHECK(entries(dir).size() == 1u);
  }
  fs::remove_all(dir);
}

TEST_CASE("program cache: a cache folder that cannot be used means source builds") {
  const fs::path dir = fresh_directory("cache-folder");
  fs::create_directories(dir);
  SUBCASE("a file") {
    write_file(dir / "file", "a file");
    const CacheDirectory set((dir / "file").string());
    CHECK(scan_built_from_source());
    CHECK(scan_built_from_source());
    CHECK(contents(dir / "file") == "a file");
  }
  SUBCASE("below a file") {
    write_file(dir / "file", "a file");
    const CacheDirectory set((dir / "file" / "cache").string());
    CHECK(scan_built_from_source());
    CHECK(scan_built_from_source());
  }
  SUBCASE("not writable") {
    fs::create_directories(dir / "read-only");
    fs::permissions(dir / "read-only", fs::perms::owner_read | fs::perms::owner_exec);
    const CacheDirectory set((dir / "read-only").string());
    CHECK(scan_built_from_source());
    if (geteuid() != 0) // root writes anyway
      CHECK(scan_built_from_source());
    fs::permissions(dir / "read-only", fs::perms::owner_all);
  }
  fs::remove_all(dir);
}

TEST_CASE("program cache: every change to an entry's bytes is refused") {
  const fs::path dir = fresh_directory("cache-bytes");
  const CacheDirectory set(dir.string());
  const clmesh::ProgramCache cache("source", "identity");
  cache.store({1, 2, 3, 4, 5, 6, 7, 8});
  REQUIRE(entries(dir).size() == 1u);
  const fs::path entry = entries(dir).front();
  const std::string whole = contents(entry);
  REQUIRE(cache.load().has_value());
  for (std::size_t size = 0; size < whole.size(); ++size) {
    write_file(entry, whole.substr(0, size));
    CHECK_FALSE(cache.load().has_value());
  }
  for (std::size_t i = 0; i < whole.size(); ++i)
    for (const int bit : {0, 7}) {
      std::string damaged = whole;
      damaged[i] = static_cast<char>(damaged[i] ^ (1 << bit));
      write_file(entry, damaged);
      CHECK_FALSE(cache.load().has_value());
    }
  write_file(entry, whole);
  CHECK(cache.load() == std::vector<unsigned char>{1, 2, 3, 4, 5, 6, 7, 8});
  fs::remove(entry);
  ::mkfifo(entry.c_str(), 0600); // would block a reader that waits for a writer
  CHECK_FALSE(cache.load().has_value());
  fs::remove_all(dir);
}

TEST_CASE("program cache: writers filling one entry at once leave it whole") {
  // Two devices on one platform share entries, and threads of one process
  // share its pid: every load sees one writer's whole binary.
  const fs::path dir = fresh_directory("cache-writers");
  const CacheDirectory set(dir.string());
  const std::size_t size = std::size_t{1} << 20;
  std::atomic<int> torn{0};
  std::vector<std::thread> writers;
  for (int w = 0; w < 4; ++w)
    writers.emplace_back([&, w] {
      const clmesh::ProgramCache cache("source", "identity");
      const std::vector<unsigned char> binary(size, static_cast<unsigned char>('a' + w));
      for (int round = 0; round < 20; ++round) {
        cache.store(binary);
        const auto loaded = cache.load();
        if (!loaded || loaded->size() != size ||
            !std::all_of(loaded->begin(), loaded->end(),
                         [&](unsigned char c) { return c == loaded->front(); }))
          ++torn;
      }
    });
  for (auto &writer : writers)
    writer.join();
  CHECK(torn.load() == 0);
  CHECK(entries(dir).size() == 1u);
  fs::remove_all(dir);
}

TEST_CASE("program cache: a store removes partial files that killed writers left") {
  const fs::path dir = fresh_directory("cache-partials");
  const CacheDirectory set(dir.string());
  fs::create_directories(dir);
  const std::string prefix = "0123456789abcdef0123456789abcdef.bin.";
  for (const char *name : {"1-0-0000000000000000.partial", "2-0-0000000000000000.partial"})
    write_file(dir / (prefix + name), "half an entry");
  write_file(dir / "notes.partial", "not clmesh's");
  const auto old = fs::file_time_type::clock::now() - std::chrono::hours(2);
  fs::last_write_time(dir / (prefix + "1-0-0000000000000000.partial"), old);
  fs::last_write_time(dir / "notes.partial", old);
  clmesh::ProgramCache("source", "identity").store({1, 2, 3});
  CHECK_FALSE(fs::exists(dir / (prefix + "1-0-0000000000000000.partial"))); // stale
  CHECK(fs::exists(dir / (prefix + "2-0-0000000000000000.partial")));       // maybe a live writer's
  CHECK(fs::exists(dir / "notes.partial"));
  CHECK(entries(dir).size() == 3u);
  fs::remove_all(dir);
}
