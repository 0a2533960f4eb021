// The device-type code paths (host/runtime/opencl_context.hpp, DevicePaths): a
// device takes the ones CLMESH_DEVICE_PATHS asks for, and the CPU and the GPU
// paths give the same meshes byte for byte (the determinism rule: output never
// depends on such choices). tests/CMakeLists.txt runs the mesh tests a second
// time with CLMESH_DEVICE_PATHS=gpu, the first test case here among them.
#include <doctest/doctest.h>

#include "clmesh/clmesh.hpp"
#include "mesh_fixtures.hpp"
#include "runtime/device_mesh.hpp"
#include "runtime/opencl_context.hpp"
#include "runtime/prefix_scan.hpp"
#include "test_support.hpp"

#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include <sys/mman.h>

using namespace clmesh;
using test_support::device;

namespace {

// Every path a device takes follows Device::cpu_paths().
void check_paths(Device &dev, bool cpu_paths) {
  CHECK(dev.cpu_paths() == cpu_paths);
  // Kernels prefetch on the CPU paths of PoCL's devices only (cl/prefetch.h),
  // and only for meshes of Tuning::prefetch_from points or more.
  const bool pocl = dev.description().platform_name == "Portable Computing Language";
  const bool cpu_device = (dev.cl_device().getInfo<CL_DEVICE_TYPE>() & CL_DEVICE_TYPE_CPU) != 0;
  for (const bool large : {true, false}) {
    CAPTURE(large);
    dev.fit_prefetching(large ? 1000 : 999, 1000);
    const cl::Program &program = dev.program("scan.cl", "test");
    const auto options = program.getBuildInfo<CL_PROGRAM_BUILD_OPTIONS>(dev.cl_device());
    CHECK((options.find("-DCLM_PREFETCH") != std::string::npos) == (pocl && cpu_paths && large));
    // The exact predicate stages out of line on a CPU device, whatever its
    // paths (cl/predicates.h).
    CHECK((options.find("-DCLM_EXACT_OUT_OF_LINE") != std::string::npos) == cpu_device);
  }
  // Scans by runs on the CPU paths, by blocks on the GPU ones.
  CHECK(PrefixScan(dev).by_runs() == cpu_paths);
#ifdef MADV_HUGEPAGE
  // A large array lives in host memory on the CPU paths only.
  const DeviceArray<cl_int> array(dev, std::size_t{1} << 20);
  CHECK(((array.buffer().getInfo<CL_MEM_FLAGS>() & CL_MEM_USE_HOST_PTR) != 0) == cpu_paths);
#endif
}

// The same mesh, and not an empty one.
void check_same_mesh(const Mesh &a, const Mesh &b) {
  CHECK(!a.triangles.empty());
  test_support::check_same_mesh(a, b);
}

// Random points with random segments between them (crossings become
// vertices); the hull is kept, so nothing is eaten.
Input random_pslg(int n, int segments, unsigned seed) {
  Input pslg;
  pslg.points = fixtures::uniform(n, seed);
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int32_t> pick(0, n - 1);
  for (int s = 0; s < segments; ++s)
    pslg.segments.push_back({pick(rng), pick(rng), s + 2});
  return pslg;
}

} // namespace

TEST_CASE("device paths: the device takes the paths CLMESH_DEVICE_PATHS asks for") {
  Device &dev = device();
  const char *env = std::getenv("CLMESH_DEVICE_PATHS");
  const std::string asked = env ? env : "";
  CAPTURE(asked);
  const bool is_cpu = (dev.cl_device().getInfo<CL_DEVICE_TYPE>() & CL_DEVICE_TYPE_CPU) != 0;
  check_paths(dev, asked == "gpu" ? false : asked == "cpu" ? true : is_cpu);
}

TEST_CASE("device paths: the CPU and the GPU paths give the same meshes") {
  // Two devices on one OpenCL device, each forced to one kind of path.
  Device &opened = device();
  Device cpu(opened.cl_device(), opened.description(), DevicePaths::cpu);
  Device gpu(opened.cl_device(), opened.description(), DevicePaths::gpu);
  check_paths(cpu, true);
  check_paths(gpu, false);

  {
    auto points = fixtures::uniform(30000, 7);
    points.insert(points.end(), points.begin(), points.begin() + 50); // duplicates
    const auto lattice = fixtures::lattice(40, 0.01, {2, 2});         // cocircular
    points.insert(points.end(), lattice.begin(), lattice.end());
    Input input;
    input.points = points;
    INFO("delaunay");
    check_same_mesh(triangulate(cpu, input, ""), triangulate(gpu, input, ""));
  }
  {
    const Input pslg = random_pslg(3000, 60, 11);
    INFO("constrained delaunay");
    const Mesh a = triangulate(cpu, pslg, "pc");
    CHECK(a.points.size() > pslg.points.size()); // crossings
    check_same_mesh(a, triangulate(gpu, pslg, "pc"));
  }
  {
    Input input;
    input.points = fixtures::gaussian(5000, 13);
    for (const auto algorithm : {RefineAlgorithm::qmv, RefineAlgorithm::qm}) {
      Options options = parse_switches("q30");
      options.tuning.use(algorithm);
      INFO("refinement, ", algorithm == RefineAlgorithm::qmv ? "GPU-QM-V" : "GPU-QM");
      const Mesh a = triangulate(cpu, input, options);
      CHECK(a.statistics.refinement.inserted > 0);
      check_same_mesh(a, triangulate(gpu, input, options));
    }
  }
  {
    // Quality meshing of a PSLG with crossings, holes carved by -p, regions and -D.
    const Input pslg = random_pslg(3000, 60, 11);
    for (const char *switches : {"pq30", "pcq25D", "pq30a0.001"}) {
      INFO("PSLG refinement ", switches);
      const Mesh a = triangulate(cpu, pslg, switches);
      CHECK(a.statistics.refinement.inserted > 0);
      check_same_mesh(a, triangulate(gpu, pslg, switches));
    }
  }
}
