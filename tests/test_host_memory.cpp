// The memory a run may use: MemAvailable, and the limits of the process's
// control groups (v1 and v2), read from a made-up /proc and /sys/fs/cgroup.
#include "runtime/host_memory.hpp"

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <unistd.h>

namespace fs = std::filesystem;

namespace {

constexpr std::size_t kMiB = std::size_t{1} << 20;

// A folder standing for `/`, removed with the object.
class FakeRoot {
public:
  FakeRoot() {
    std::random_device seed;
    path_ = fs::temp_directory_path() / ("clmesh-host-memory-" + std::to_string(seed()));
    fs::create_directories(path_ / "proc/self");
    write("proc/self/statm", "5000 100 0 0 0 0 0\n"); // 100 pages resident
  }
  ~FakeRoot() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  void write(const std::string &file, const std::string &text) const {
    fs::create_directories((path_ / file).parent_path());
    std::ofstream(path_ / file) << text;
  }
  void available(std::size_t bytes) const {
    write("proc/meminfo", "MemTotal:       24000000 kB\nMemFree:  1000 kB\nMemAvailable:   " +
                              std::to_string(bytes / 1024) + " kB\nBuffers: 10 kB\n");
  }
  std::string path() const { return path_.string(); }

private:
  fs::path path_;
};

std::size_t resident() { return 100 * static_cast<std::size_t>(sysconf(_SC_PAGESIZE)); }

const char *kV1Mounts =
    "25 1 0:23 / /sys rw - sysfs sysfs rw\n"
    "31 25 0:28 / /sys/fs/cgroup rw,relatime - tmpfs tmpfs rw,mode=755\n"
    "32 31 0:29 / /sys/fs/cgroup/cpu rw,relatime shared:9 - cgroup cgroup rw,cpu\n"
    "35 31 0:32 / /sys/fs/cgroup/memory rw,relatime shared:12 - cgroup cgroup rw,memory\n";

} // namespace

TEST_CASE("host memory: MemAvailable and the resident set when no group limits") {
  const FakeRoot root;
  root.available(20000 * kMiB);
  const auto room = clmesh::host_memory_for_process(root.path());
  REQUIRE(room.has_value());
  CHECK(*room == 20000 * kMiB + resident());
}

TEST_CASE("host memory: no /proc/meminfo, no figure") {
  const FakeRoot root;
  CHECK_FALSE(clmesh::host_memory_for_process(root.path()).has_value());
}

TEST_CASE("host memory: cgroup v1, the tightest limit of the group and those above it") {
  const FakeRoot root;
  root.available(20000 * kMiB);
  root.write("proc/self/cgroup", "5:cpu,cpuacct:/\n4:memory:/jobs/job7/step0\n0::/\n");
  root.write("proc/self/mountinfo", kV1Mounts);
  const std::string memory = "sys/fs/cgroup/memory";
  // The root group and the step: no limit (v1 writes it as a huge number).
  root.write(memory + "/memory.limit_in_bytes", "9223372036854771712\n");
  root.write(memory + "/jobs/job7/step0/memory.limit_in_bytes", "9223372036854771712\n");
  root.write(memory + "/jobs/job7/step0/memory.usage_in_bytes", "300000000\n");
  // The job: 1024 MiB, 600 MiB used of which 100 MiB inactive file cache.
  root.write(memory + "/jobs/job7/memory.limit_in_bytes", std::to_string(1024 * kMiB) + "\n");
  root.write(memory + "/jobs/job7/memory.usage_in_bytes", std::to_string(600 * kMiB) + "\n");
  root.write(memory + "/jobs/job7/memory.stat",
             "cache 1\ninactive_file 7\ntotal_inactive_file " + std::to_string(100 * kMiB) + "\n");
  // Above: 4096 MiB, 1000 MiB used.
  root.write(memory + "/jobs/memory.limit_in_bytes", std::to_string(4096 * kMiB) + "\n");
  root.write(memory + "/jobs/memory.usage_in_bytes", std::to_string(1000 * kMiB) + "\n");
  auto room = clmesh::host_memory_for_process(root.path());
  REQUIRE(room.has_value());
  CHECK(*room == 524 * kMiB + resident());

  SUBCASE("the system has less available than the limits leave") {
    root.available(200 * kMiB);
    room = clmesh::host_memory_for_process(root.path());
    REQUIRE(room.has_value());
    CHECK(*room == 200 * kMiB + resident());
  }
  SUBCASE("a group over its limit leaves nothing but what the process holds") {
    root.write(memory + "/jobs/memory.usage_in_bytes", std::to_string(5000 * kMiB) + "\n");
    room = clmesh::host_memory_for_process(root.path());
    REQUIRE(room.has_value());
    CHECK(*room == resident());
  }
}

TEST_CASE("host memory: cgroup v2, memory.max of the group and those above it") {
  const FakeRoot root;
  root.available(20000 * kMiB);
  root.write("proc/self/cgroup", "0::/user.slice/run-1.scope\n");
  root.write("proc/self/mountinfo",
             "25 1 0:23 / /sys rw - sysfs sysfs rw\n"
             "30 25 0:26 / /sys/fs/cgroup rw,nosuid shared:4 - cgroup2 cgroup2 rw,nsdelegate\n");
  const std::string unified = "sys/fs/cgroup";
  root.write(unified + "/user.slice/run-1.scope/memory.max", "max\n");
  root.write(unified + "/user.slice/run-1.scope/memory.current", "1000\n");
  root.write(unified + "/user.slice/memory.max", std::to_string(2048 * kMiB) + "\n");
  root.write(unified + "/user.slice/memory.current", std::to_string(1536 * kMiB) + "\n");
  root.write(unified + "/user.slice/memory.stat",
             "anon 5\nfile 9\ninactive_file " + std::to_string(12 * kMiB) + "\n");
  const auto room = clmesh::host_memory_for_process(root.path());
  REQUIRE(room.has_value());
  CHECK(*room == 524 * kMiB + resident());
}

TEST_CASE("host memory: a container's view starts at its own group") {
  // Without a cgroup namespace the container sees the host's path of its
  // group, and the mount shows the hierarchy from that group down.
  const FakeRoot root;
  root.available(20000 * kMiB);
  root.write("proc/self/cgroup", "0::/system.slice/docker-ab12.scope\n");
  root.write("proc/self/mountinfo", "30 25 0:26 /system.slice/docker-ab12.scope /sys/fs/cgroup "
                                    "ro,nosuid - cgroup2 cgroup2 rw\n");
  root.write("sys/fs/cgroup/memory.max", std::to_string(512 * kMiB) + "\n");
  root.write("sys/fs/cgroup/memory.current", std::to_string(12 * kMiB) + "\n");
  const auto room = clmesh::host_memory_for_process(root.path());
  REQUIRE(room.has_value());
  CHECK(*room == 500 * kMiB + resident());
}
