// The Vulkan passes against the cpu's (the same rules, tables and operation order: positions are
// meant to be bit-identical), watertight on their own output, on the Catmull-Clark corpus sweep
// at depths 1..5 (harness/conformance/backend_agreement.h); every pass timed. Skipped without a
// Vulkan device.
#include <gtest/gtest.h>

#include "harness/conformance/backend_agreement.h"
#include "harness/conformance/sweep_corpus.h"
#include "harness/core/registry.h"
#include "harness/gpu/testing.h"
#include "schemes/edgefriend/edgefriend.h"

using namespace sdb;

namespace {

class EdgeFriendVulkan : public gpu::testing::VulkanTest {};
constexpr SubdivisionRule kCC = SubdivisionRule::CatmullClark;

std::unique_ptr<Evaluation> evaluation(const ControlMesh& m, int depth, Backend b) {
  const SchemeInfo& info = find_scheme("edgefriend-cc")->info();
  return edgefriend::make_evaluation(m, default_request(info, b, depth), true);
}

TEST_F(EdgeFriendVulkan, CorpusMatchesTheCpu) {
  conformance::vulkan_sweep(
      kCC, "edgefriend-cc", [&](const ControlMesh& m) { evaluation(m, 1, Backend::Cpu); },
      [&](const std::string& name, const ControlMesh& m, int depth) {
        return conformance::expect_vulkan_agrees(
            name, depth, m,
            [&](Backend b) {
              auto e = evaluation(m, depth, b);
              e->execute();
              return e->result();
            },
            {.max_rel = 1e-6, .max_deg = 1e-3, .open_edges = conformance::boundary_edges(m) << depth, .rays = 20000});
      });
}

// The first step, every level's kernel and the limit's passes are timed, and the kernel time is
// their sum.
TEST_F(EdgeFriendVulkan, EveryPassIsTimed) {
  const ControlMesh m = conformance::sweep_mesh("crane/spot_control", kCC, "edgefriend-cc");
  conformance::expect_passes_timed(*evaluation(m, 3, Backend::Vulkan),
                                   {"upload", "depth 1: first step", "depth 2: edge-friend", "depth 3: edge-friend",
                                    "limit: regular", "limit: special", "readback"});
}

}  // namespace
