// The device for calls that name none (api/device_choice.hpp): how inputs are
// weighed, which devices PoCL offers after the request, and that the
// in-thread and multi-threaded devices give the same meshes.
#include <doctest/doctest.h>

#include "api/device_choice.hpp"
#include "clmesh/clmesh.hpp"
#include "mesh_fixtures.hpp"
#include "test_support.hpp"

#include <cstdlib>
#include <string>

using test_support::check_same_mesh;

TEST_CASE("device choice: an input's size counts points, segments, triangles and the area bound") {
  clmesh::Input input;
  input.points = {{0, 0}, {2, 0}, {2, 1}, {0, 1}};
  input.segments = {{0, 1, 1}, {1, 2, 1}};
  input.triangles = {{0, 1, 2}};
  clmesh::Options options;
  CHECK(clmesh::input_size(input, options) == 7);
  options.max_area = 0.001; // the 2 x 1 box over the bound: 2000 more
  CHECK(clmesh::input_size(input, options) == 2007);
  options.max_area = 1e-300;
  CHECK(clmesh::input_size(input, options) == static_cast<std::size_t>(1e18));
}

TEST_CASE("device choice: a named device serves every input") {
  for (const auto meshing : {clmesh::Meshing::one_input, clmesh::Meshing::batch}) {
    const clmesh::DeviceSpecs specs = clmesh::device_specs("0", meshing);
    CHECK(specs.small_inputs == "0");
    CHECK(specs.large_inputs == "0");
  }
}

// Its own process (each test case is its own CTest test): the request comes
// before OpenCL starts, unless the environment already chose.
TEST_CASE("device choice: on PoCL, small inputs on the in-thread device, the same meshes") {
  const bool chosen = std::getenv("CLMESH_DEVICE") || std::getenv("POCL_DEVICES");
  clmesh::offer_pocl_drivers("");
  const clmesh::DeviceSpecs specs = clmesh::device_specs("", clmesh::Meshing::one_input);
  CHECK(clmesh::device_specs("", clmesh::Meshing::batch).small_inputs == specs.small_inputs);
  const clmesh::DeviceDescription first = clmesh::find_device("");
  if (chosen || first.platform_name != "Portable Computing Language") {
    CHECK(specs.small_inputs == specs.large_inputs); // the default device serves all
    return;
  }
  REQUIRE(specs.small_inputs != specs.large_inputs);
  const clmesh::DeviceDescription in_thread = clmesh::find_device(specs.small_inputs);
  const clmesh::DeviceDescription multi_threaded = clmesh::find_device(specs.large_inputs);
  CHECK(in_thread.device_name.rfind("basic", 0) == 0);
  CHECK(multi_threaded.device_name.rfind("pthread", 0) == 0);

  clmesh::Input input;
  input.points = fixtures::uniform(2000, 3);
  for (const char *switches : {"", "q30", "q25a0.0005"}) {
    CAPTURE(switches);
    const clmesh::Options options = clmesh::parse_switches(switches);
    auto small = clmesh::open_device(specs.small_inputs);
    auto large = clmesh::open_device(specs.large_inputs);
    check_same_mesh(clmesh::triangulate(*small, input, options),
                    clmesh::triangulate(*large, input, options));
    // triangulate(input, options) takes the in-thread device for it.
    const clmesh::Mesh shared = clmesh::triangulate(input, options);
    CHECK(shared.statistics.delaunay.device.find(in_thread.device_name) != std::string::npos);
    check_same_mesh(shared, clmesh::triangulate(*large, input, options));
  }
}

namespace {

clmesh::DeviceDescription described(int platform, int device, const std::string &platform_name,
                                    const std::string &device_name, bool is_cpu) {
  clmesh::DeviceDescription description;
  description.platform_index = platform;
  description.device_index = device;
  description.platform_name = platform_name;
  description.device_name = device_name;
  description.has_fp64 = true;
  description.is_cpu = is_cpu;
  return description;
}

} // namespace

TEST_CASE("device choice: which devices serve small and large inputs, by the devices found") {
  using clmesh::Meshing;
  const std::string pocl = "Portable Computing Language";
  const auto gpu = described(0, 0, "NVIDIA CUDA", "NVIDIA H200", false);
  // PoCL up to 4 names its devices by driver, later ones "cpu-minimal" and "cpu".
  for (const auto &[in_thread, threaded] :
       {std::pair<std::string, std::string>{"basic-x86", "pthread-x86"},
        std::pair<std::string, std::string>{"cpu-minimal-x86", "cpu-x86"}}) {
    CAPTURE(in_thread);
    const auto minimal = described(1, 1, pocl, in_thread, true);
    const auto multi = described(1, 0, pocl, threaded, true);
    for (const Meshing meshing : {Meshing::one_input, Meshing::batch}) {
      CAPTURE(static_cast<int>(meshing));
      SUBCASE("PoCL first: its in-thread device, then its multi-threaded one") {
        const auto specs = clmesh::choose_devices({multi, minimal}, multi, "", meshing);
        CHECK(specs.small_inputs == "1:1");
        CHECK(specs.large_inputs == "1:0");
        // A batch keeps every CPU busy with its workers: larger inputs stay
        // on the in-thread device than for one input meshed alone.
        CHECK(specs.large_from ==
              (meshing == Meshing::batch ? clmesh::kLargeInBatch : clmesh::kLargeAlone));
      }
      SUBCASE("PoCL without its in-thread device: the default device for all") {
        for (const auto &first : {multi, gpu}) {
          const auto specs = clmesh::choose_devices({gpu, multi}, first, "", meshing);
          CHECK(specs.small_inputs == "");
          CHECK(specs.large_inputs == "");
        }
      }
    }
    SUBCASE("a GPU first: in a batch PoCL's in-thread device for small inputs, else the GPU") {
      const auto batch = clmesh::choose_devices({gpu, multi, minimal}, gpu, "", Meshing::batch);
      CHECK(batch.small_inputs == "1:1");
      CHECK(batch.large_inputs == "");
      CHECK(batch.large_from == clmesh::kLargeInBatch);
      const auto alone = clmesh::choose_devices({gpu, multi, minimal}, gpu, "", Meshing::one_input);
      CHECK(alone.small_inputs == "");
      CHECK(alone.large_inputs == "");
    }
  }
  SUBCASE("a GPU alone, or another CPU platform first: the default device for all") {
    const auto minimal = described(2, 0, pocl, "cpu-minimal-x86", true);
    const auto other_cpu = described(1, 0, "Intel(R) OpenCL", "Intel(R) Xeon(R)", true);
    for (const auto &[devices, first] :
         {std::pair<std::vector<clmesh::DeviceDescription>, clmesh::DeviceDescription>{{gpu}, gpu},
          {{other_cpu, minimal}, other_cpu}}) {
      const auto specs = clmesh::choose_devices(devices, first, "", Meshing::batch);
      CHECK(specs.small_inputs == "");
      CHECK(specs.large_inputs == "");
    }
  }
}
