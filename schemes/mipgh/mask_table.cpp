#include "schemes/mipgh/mask_table.h"

#include <algorithm>
#include <array>

namespace sdb::mipgh {
namespace {

// One entry's terms, merged by source node (in double, rounded once).
template <int W>
struct Terms {
  std::vector<std::pair<uint32_t, std::array<double, W>>> terms;
  void add(V3 p, int k, float w) {
    const uint32_t s = node_of(p);
    auto it = std::find_if(terms.begin(), terms.end(), [&](const auto& t) { return t.first == s; });
    if (it == terms.end()) it = terms.insert(terms.end(), {s, {}});
    it->second[k] += w;
  }
  void append_to(MaskTable& table, uint32_t target) {
    table.target.push_back(target);
    for (const auto& [s, w] : terms) {
      table.source.push_back(s);
      for (double x : w) table.weight.push_back(float(x));
    }
    table.begin.push_back(uint32_t(table.source.size()));
    terms.clear();
  }
};

}  // namespace

std::vector<V3> node_ids(uint32_t count) {
  std::vector<V3> ids(count);
  for (uint32_t i = 0; i < count; ++i) ids[i] = {float(i & 0xFFFFFFu), float(i >> 24), 0.0f};
  return ids;
}

uint32_t node_of(V3 p) { return uint32_t(p.x) | (uint32_t(p.y) << 24); }

MaskTable build_mask_table(const MeshProcessor& processor, const MeshShader& shader, const DLoD& lod, int sigma,
                           bool limit) {
  const std::vector<V3> ids = node_ids(lod.layout(sigma).num_nodes);
  MaskTable table;
  table.begin.push_back(0);
  SdcMask masks[3];
  Terms<1> step;
  Terms<3> projection;
  processor.shader_disks(sigma, ids.data(), limit, [&](uint32_t target, const VertexDisk* v, const EdgeDisk* e) {
    if (v && v->edges == 0) {  // copied
      if (limit) projection.add(v->c, 0, 1.0f), projection.append_to(table, target);
      else step.add(v->c, 0, 1.0f), step.append_to(table, target);
      return;
    }
    if (limit) {
      shader.limit_masks(*v, masks[0], masks[1], masks[2]);
      for (int k = 0; k < 3; ++k) for_each_term(masks[k], *v, [&](V3 p, float w) { projection.add(p, k, w); });
      projection.append_to(table, target);
      return;
    }
    if (v) {
      shader.vertex_mask(*v, masks[0]);
      for_each_term(masks[0], *v, [&](V3 p, float w) { step.add(p, 0, w); });
    } else {
      shader.edge_mask(*e, masks[0]);
      for_each_term(masks[0], *e, [&](V3 p, float w) { step.add(p, 0, w); });
    }
    step.append_to(table, target);
  });
  return table;
}

}  // namespace sdb::mipgh
