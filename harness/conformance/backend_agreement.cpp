#include "harness/conformance/backend_agreement.h"

#include <gtest/gtest.h>

#include <cstdio>

#include "harness/core/errors.h"
#include "harness/mesh/facts.h"
#include "harness/conformance/sweep_corpus.h"
#include "harness/validate/watertight.h"

namespace sdb::conformance {

Agreement expect_vulkan_agrees(const std::string& name, int depth, const ControlMesh& accepted, const BackendRun& run,
                               const VulkanExpectations& e) {
  const Tessellation cpu = run(Backend::Cpu);
  Tessellation gpu;
  try {
    gpu = run(Backend::Vulkan);
  } catch (const Unsupported& why) {
    std::printf("  %s depth %d refused on this device: %s\n", name.c_str(), depth, why.what());
    return {};
  }
  EXPECT_EQ(cpu.triangles, gpu.triangles) << name;
  if (cpu.positions.size() != gpu.positions.size()) {
    ADD_FAILURE() << name << ": the backends lay the output out differently";
    return {};
  }
  const Agreement a = agreement(cpu, gpu, bounds_of(accepted.positions).diagonal());
  EXPECT_LE(a.max_rel, e.max_rel) << name << " depth " << depth;
  EXPECT_LE(a.max_deg, e.max_deg) << name << " depth " << depth;
  EXPECT_EQ(count_open_edges(gpu), e.open_edges >= 0 ? e.open_edges : count_open_edges(cpu))
      << name << " depth " << depth;
  if (e.rays > 0 && compute_facts(accepted).closed && accepted.holes.empty()) {
    const RayCrackReport r = ray_crack_check(gpu, {e.rays / 2, e.rays / 2, 3});
    EXPECT_EQ(r.cracks, 0) << name << " depth " << depth << " (" << r.rays << " rays)";
  }
  return a;
}

void vulkan_sweep(SubdivisionRule rule, const std::string& scheme,
                  const std::function<void(const ControlMesh&)>& cpu_prepare, const SweepCheck& check) {
  const std::vector<std::string> shapes = sweep_shapes(rule);
  if (shapes.empty()) GTEST_SKIP() << "no shared corpus";
  size_t identical = 0, vertices = 0;
  double worst = 0, worst_deg = 0;
  int runs = 0, refused = 0;
  for (const std::string& name : shapes) {
    ControlMesh accepted;
    try {
      accepted = sweep_mesh(name, rule, scheme);
      cpu_prepare(accepted);
    } catch (const std::exception& e) {  // refused on the cpu too, with the reason (the scheme's own tests list them)
      if (!dynamic_cast<const InputError*>(&e) && !dynamic_cast<const Unsupported*>(&e)) throw;
      std::printf("  refused %s: %s\n", name.c_str(), e.what());
      ++refused;
      continue;
    }
    const long faces = num_faces(accepted) - static_cast<long>(accepted.holes.size());
    for (int depth = 1; depth <= 5; ++depth) {
      if (depth > 1 && faces * (rule == SubdivisionRule::Loop ? 1L : 2L) << (2 * depth) > 20000) break;
      Agreement a;
      try {
        a = check(name, accepted, depth);
      } catch (const Unsupported& e) {  // refused up front by the scheme with its reason, as on the cpu
        std::printf("  refused %s depth %d: %s\n", name.c_str(), depth, e.what());
        ++refused;
        break;
      }
      if (a.vertices == 0) continue;  // refused by the device, said
      identical += a.identical, vertices += a.vertices, ++runs;
      worst = std::max(worst, a.max_rel), worst_deg = std::max(worst_deg, a.max_deg);
    }
  }
  std::printf("%s: %d runs (%d refused up front), %zu of %zu positions bit-identical to the cpu's, worst %.2g of the "
              "diagonal, normals %.2g deg\n", scheme.c_str(), runs, refused, identical, vertices, worst, worst_deg);
}

void expect_passes_timed(Evaluation& e, const std::vector<std::string>& expected) {
  e.execute();
  e.result();
  const std::optional<GpuTimes> t = e.gpu_times();
  if (!t) GTEST_SKIP() << "no timestamps on this queue";
  std::vector<std::string> labels;
  double kernel = 0;
  for (const GpuPassTime& p : t->passes) {
    labels.push_back(p.label);
    if (p.label != "upload" && p.label != "readback") kernel += p.ms;
  }
  EXPECT_EQ(labels, expected);
  EXPECT_NEAR(t->kernel_ms, kernel, 1e-9);
}

}  // namespace sdb::conformance
