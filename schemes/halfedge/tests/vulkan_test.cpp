// The Vulkan passes against the cpu's (the same rules, tables and operation order: positions are
// meant to be bit-identical), watertight on their own output, on the corpus sweep of each rule at
// depths 1..5 (harness/conformance/backend_agreement.h); their passes timed. Skipped without a
// Vulkan device.
#include <gtest/gtest.h>

#include <cstdio>

#include "harness/conformance/backend_agreement.h"
#include "harness/conformance/sweep_corpus.h"
#include "harness/core/registry.h"
#include "harness/gpu/testing.h"
#include "harness/mesh/osd_topology.h"
#include "harness/refined/limit_vulkan.h"
#include "schemes/halfedge/halfedge.h"

using namespace sdb;

namespace {

class HalfedgeVulkan : public gpu::testing::VulkanTest {};

const char* scheme_name(SubdivisionRule rule) { return rule == SubdivisionRule::Loop ? "halfedge-loop" : "halfedge-cc"; }

std::unique_ptr<Evaluation> evaluation(const ControlMesh& m, SubdivisionRule rule, int depth, Backend b) {
  const SchemeInfo& info = find_scheme(scheme_name(rule))->info();
  return halfedge::make_evaluation(m, rule, default_request(info, b, depth), true);
}

void sweep(SubdivisionRule rule) {
  conformance::vulkan_sweep(
      rule, scheme_name(rule), [&](const ControlMesh& m) { evaluation(m, rule, 1, Backend::Cpu); },
      [&](const std::string& name, const ControlMesh& m, int depth) {
        return conformance::expect_vulkan_agrees(
            name, depth, m,
            [&](Backend b) {
              auto e = evaluation(m, rule, depth, b);
              e->execute();
              return e->result();
            },
            {.max_rel = 1e-6, .max_deg = 1e-3, .open_edges = conformance::boundary_edges(m) << depth, .rays = 20000});
      });
}

TEST_F(HalfedgeVulkan, CatmullClarkCorpusMatchesTheCpu) { sweep(SubdivisionRule::CatmullClark); }
TEST_F(HalfedgeVulkan, LoopCorpusMatchesTheCpu) { sweep(SubdivisionRule::Loop); }

// Every level's passes and the limit's are timed, and the kernel time is their sum.
TEST_F(HalfedgeVulkan, EveryPassIsTimed) {
  const ControlMesh m = conformance::sweep_mesh("crane/spot_control", SubdivisionRule::CatmullClark, "halfedge-cc");
  conformance::expect_passes_timed(*evaluation(m, SubdivisionRule::CatmullClark, 3, Backend::Vulkan),
                                   {"upload", "depth 1: faces", "depth 1: edges", "depth 1: vertices", "depth 2: faces",
                                    "depth 2: edges", "depth 2: vertices", "depth 3: faces", "depth 3: edges",
                                    "depth 3: vertices", "limit: regular", "limit: special", "readback"});
}

// The limit's regular rings split across views (the sword's depth 5 has 183 M entries, one view of
// lavapipe's 134 M) give the very output of one view, and the cpu's: here views of 1,000 vertices'
// rings, which cut spot's depth 3 (11,522 vertices) and the bunny's depth 2 into a dozen or more.
TEST_F(HalfedgeVulkan, RingsInSeveralViewsGiveOneViewsOutput) {
  for (SubdivisionRule rule : {SubdivisionRule::CatmullClark, SubdivisionRule::Loop}) {
    const bool loop = rule == SubdivisionRule::Loop;
    const ControlMesh m = conformance::sweep_mesh(loop ? "stanford/bunny" : "crane/spot_control", rule, scheme_name(rule));
    const int depth = loop ? 2 : 3;
    auto run = [&](Backend b) {
      auto e = evaluation(m, rule, depth, b);
      e->execute();
      return e->result();
    };
    const Tessellation cpu = run(Backend::Cpu), one_view = run(Backend::Vulkan);
    refined::limit_ring_view_entries_for_testing(1000 * (loop ? 6 : 8));
    const Tessellation views = run(Backend::Vulkan);
    refined::limit_ring_view_entries_for_testing(0);
    ASSERT_GT(views.positions.size(), 10000u);
    ASSERT_EQ(views.positions.size(), one_view.positions.size());
    size_t differ = 0, differ_cpu = 0;
    for (size_t v = 0; v < views.positions.size(); ++v) {
      differ += views.positions[v] != one_view.positions[v] || views.normals[v] != one_view.normals[v];
      differ_cpu += views.positions[v] != cpu.positions[v] || views.normals[v] != cpu.normals[v];
    }
    std::printf("%s depth %d: %zu vertices in views of 1,000, %zu differ from one view's, %zu from the cpu's\n",
                scheme_name(rule), depth, views.positions.size(), differ, differ_cpu);
    EXPECT_EQ(differ, 0u);
    EXPECT_EQ(differ_cpu, 0u);
  }
}

}  // namespace
