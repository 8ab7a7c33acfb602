// The Vulkan backend against the CPU's (the same tables and arithmetic: positions are meant to be
// bit-identical), watertight on its own output, on built-in meshes and the corpus sweep; its
// passes timed; many waves giving the output one wave gives. Skipped without a Vulkan device.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "datasets/generators.h"
#include "datasets/manifest.h"
#include "harness/core/errors.h"
#include "harness/core/registry.h"
#include "harness/gpu/testing.h"
#include "harness/mesh/acceptance.h"
#include "harness/mesh/facts.h"
#include "harness/mesh/osd_topology.h"
#include "harness/validate/watertight.h"
#include "schemes/fragments/fragments.h"
#include "harness/conformance/backend_agreement.h"
#include "harness/conformance/sweep_corpus.h"
#include "schemes/fragments/vulkan.h"

using namespace sdb;

namespace {

using conformance::boundary_edges;

class FragmentsVulkan : public gpu::testing::VulkanTest {};

const char* scheme_name(SubdivisionRule rule) { return rule == SubdivisionRule::Loop ? "fragments-loop" : "fragments-cc"; }

struct Output {
  Tessellation t;
  std::optional<GpuTimes> times;
  fragments::FragmentStats stats;
};

Output run(const ControlMesh& accepted, SubdivisionRule rule, int depth, Backend backend,
        fragments::VulkanOptions options = {}) {
  std::unique_ptr<Evaluation> e;
  if (backend == Backend::Vulkan) {
    e = fragments::make_vulkan_evaluation(accepted, rule, depth, true, options);
  } else {
    const SchemeInfo& info = find_scheme(scheme_name(rule))->info();
    e = fragments::make_evaluation(accepted, rule, default_request(info, backend, depth));
  }
  e->execute();
  Output r{e->result(), std::nullopt, fragments::stats_of(*e)};
  r.times = e->gpu_times();
  return r;
}

using conformance::Agreement;

// cpu and vulkan agree (<= 1e-6 of the diagonal, normals 1e-3 degrees), lay the output out the
// same, and the vulkan output is watertight: the input's boundary times 2^depth open, no crack.
Agreement check(const std::string& name, const ControlMesh& accepted, SubdivisionRule rule, int depth, long rays) {
  return conformance::expect_vulkan_agrees(
      name, depth, accepted, [&](Backend b) { return run(accepted, rule, depth, b).t; },
      {.max_rel = 1e-6, .max_deg = 1e-3, .open_edges = boundary_edges(accepted) << depth, .rays = rays});
}

TEST_F(FragmentsVulkan, MatchesTheCpuAndIsWatertightOnBuiltins) {
  for (const char* mesh : {"torus-8x8", "icosphere", "creased-cube", "pole3", "pole8", "quadsphere"})
    for (SubdivisionRule rule : {SubdivisionRule::CatmullClark, SubdivisionRule::Loop}) {
      const SchemeInfo& info = find_scheme(scheme_name(rule))->info();
      ControlMesh accepted;
      try {
        accepted = accept_mesh(load_mesh(mesh), info);
      } catch (const InputError&) {
        continue;  // Loop takes triangle meshes only
      }
      for (int depth = 1; depth <= 4; ++depth) {
        const Agreement a = check(std::string(mesh) + " " + info.name, accepted, rule, depth, 100000);
        std::printf("  %-12s %-15s depth %d: %zu of %zu positions bit-identical, %.2g of the diagonal, normals %.2g deg\n",
                    mesh, info.name.c_str(), depth, a.identical, a.vertices, a.max_rel, a.max_deg);
      }
    }
}

// Where a fragment's block is one polynomial (a regular patch), the device takes its normals the
// CPU's way (patch_normals.comp, kernel.cpp's patch_tangents): the same bits. torus-8x8 is
// regular patches alone; the icosphere's are Loop's regular patches and vertex patches, whose net
// normals come out the same here too (before the patch pass the torus differed by 2e-5 degrees).
TEST_F(FragmentsVulkan, PatchNormalsAreTheCpusBits) {
  for (auto [mesh, rule] :
       {std::pair{"torus-8x8", SubdivisionRule::CatmullClark}, std::pair{"icosphere", SubdivisionRule::Loop}}) {
    const ControlMesh accepted = accept_mesh(load_mesh(mesh), find_scheme(scheme_name(rule))->info());
    for (int depth = 1; depth <= 4; ++depth) {
      const Output cpu = run(accepted, rule, depth, Backend::Cpu), gpu = run(accepted, rule, depth, Backend::Vulkan);
      ASSERT_EQ(cpu.t.normals.size(), gpu.t.normals.size());
      size_t identical = 0;
      for (size_t i = 0; i < cpu.t.normals.size(); ++i) identical += cpu.t.normals[i] == gpu.t.normals[i];
      std::printf("  %-10s %-15s depth %d: %zu of %zu normals bit-identical\n", mesh, scheme_name(rule), depth,
                  identical, cpu.t.normals.size());
      EXPECT_EQ(identical, cpu.t.normals.size()) << mesh << " depth " << depth;
    }
  }
}

TEST_F(FragmentsVulkan, TimesUploadEveryLevelTheLimitAndReadback) {
  const ControlMesh accepted = accept_mesh(load_mesh("icosphere"), find_scheme("fragments-loop")->info());
  const Output r = run(accepted, SubdivisionRule::Loop, 3, Backend::Vulkan);
  ASSERT_TRUE(r.times.has_value());
  std::vector<std::string> labels;
  for (const GpuPassTime& p : r.times->passes) labels.push_back(p.label);
  EXPECT_EQ(labels, (std::vector<std::string>{"upload", "gather", "level 1", "level 2", "level 3", "limit", "readback"}));
  EXPECT_GT(r.times->kernel_ms, 0.0);
}

TEST_F(FragmentsVulkan, ManyWavesGiveTheOutputOfOne) {
  const ControlMesh accepted = accept_mesh(load_mesh("icosphere"), find_scheme("fragments-cc")->info());
  const Output one = run(accepted, SubdivisionRule::CatmullClark, 3, Backend::Vulkan);
  const Output many = run(accepted, SubdivisionRule::CatmullClark, 3, Backend::Vulkan, {uint64_t(5) << 18});
  EXPECT_EQ(one.stats.waves, 1);
  EXPECT_GT(many.stats.waves, 2);
  EXPECT_TRUE(one.t.positions == many.t.positions);
  EXPECT_TRUE(one.t.normals == many.t.normals);
}

// Depths 1..5 while the output stays small for lavapipe (conformance::vulkan_sweep); 100,000 rays
// a run. llvmpipe refuses the valence-360 poles (vulkan.cpp: its loop limit).
void sweep(SubdivisionRule rule) {
  const SchemeInfo& info = find_scheme(scheme_name(rule))->info();
  conformance::vulkan_sweep(
      rule, info.name, [&](const ControlMesh& m) { fragments::make_evaluation(m, rule, default_request(info, Backend::Cpu, 0)); },
      [&](const std::string& name, const ControlMesh& m, int depth) { return check(name, m, rule, depth, 100000); });
}

class FragmentsVulkanSweep : public gpu::testing::VulkanTest {};
TEST_F(FragmentsVulkanSweep, CatmullClarkCorpusMatchesTheCpuAndIsWatertight) { sweep(SubdivisionRule::CatmullClark); }
TEST_F(FragmentsVulkanSweep, LoopCorpusMatchesTheCpuAndIsWatertight) { sweep(SubdivisionRule::Loop); }

}  // namespace
