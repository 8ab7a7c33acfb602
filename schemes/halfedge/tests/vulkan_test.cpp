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

}  // namespace
