// The nodes the Vulkan passes' GLSL stencils leave out (vulkan.h): every D-vertex and the nodes of
// D-edges that are tagged, on a global boundary or between a quad and a triangle. Their masks
// depend on the D-atlas and the edge tags alone, both fixed after initialization (Section 3.2), so
// prepare gathers each one's 1-disk once, with the CPU processor's own gather, has the mesh
// shader's Sdc masks weigh it, and keeps the weighted source nodes; a pass applies them. The GPU
// then runs the same masks as the CPU's shader without a port of Sdc's crease rules to GLSL.
#pragma once

#include <cstdint>
#include <vector>

#include "schemes/mipgh/processor.h"
#include "schemes/mipgh/shader.h"

namespace sdb::mipgh {

struct MaskTable {
  std::vector<uint32_t> target;  // node made, per entry
  std::vector<uint32_t> begin;   // entry k's terms: begin[k] .. begin[k + 1]
  std::vector<uint32_t> source;  // per term
  // Per term: one weight (a step) or three (the limit: position, T1, T2). Terms of one source
  // node are merged.
  std::vector<float> weight;
  size_t entries() const { return target.size(); }
};

// Node indices as positions a processor gathers, so that a gathered 1-disk names its nodes (a
// float holds 24 bits exactly; the rest go in y).
std::vector<V3> node_ids(uint32_t count);
uint32_t node_of(V3 p);

// Step sigma -> sigma + 1's masks (limit = false) or the limit projection's at level sigma.
// Adaptive (DLoD's labels): a step's for what it makes of the held nodes (the interpolated and
// copied ones too), the projection's for `homes` only.
MaskTable build_mask_table(const MeshProcessor& processor, const MeshShader& shader, const DLoD& lod, int sigma,
                           bool limit, const LevelHomes& homes = {});

}  // namespace sdb::mipgh
