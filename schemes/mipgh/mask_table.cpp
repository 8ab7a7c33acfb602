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

// The nodes a disk names (node_ids), each once, with the slots holding it.
template <class Disk>
std::vector<V3*> slots(Disk& d);
template <>
std::vector<V3*> slots(VertexDisk& d) {
  std::vector<V3*> s{&d.c};
  for (V3& e : d.e) s.push_back(&e);
  for (V3& f : d.d) s.push_back(&f);
  return s;
}
template <>
std::vector<V3*> slots(EdgeDisk& d) {
  std::vector<V3*> s{&d.v0, &d.v1};
  for (int i = 0; i < d.faces; ++i) s.push_back(&d.f[i][0]), s.push_back(&d.f[i][1]);
  return s;
}

// A rule's weights by probing it: with every node 0 but one at x = 1, the rule's x is that node's
// weight (the rules are linear; the one nonzero term is rounded once, as a float weight).
template <class Disk, class Rule>
void probe(const Disk& disk, Rule&& rule, Terms<1>& step) {
  Disk unit = disk;
  const std::vector<V3*> at = slots(unit);
  std::vector<uint32_t> ids;
  for (const V3* p : at) ids.push_back(node_of(*p));
  std::vector<uint32_t> distinct = ids;
  std::sort(distinct.begin(), distinct.end());
  distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
  for (uint32_t id : distinct) {
    for (size_t k = 0; k < at.size(); ++k) *at[k] = ids[k] == id ? V3{1, 0, 0} : V3{0, 0, 0};
    const float w = rule(unit).x;
    if (w != 0) step.add(V3{float(id & 0xFFFFFFu), float(id >> 24), 0.0f}, 0, w);
  }
}

}  // namespace

std::vector<V3> node_ids(uint32_t count) {
  std::vector<V3> ids(count);
  for (uint32_t i = 0; i < count; ++i) ids[i] = {float(i & 0xFFFFFFu), float(i >> 24), 0.0f};
  return ids;
}

uint32_t node_of(V3 p) { return uint32_t(p.x) | (uint32_t(p.y) << 24); }

MaskTable build_mask_table(const MeshProcessor& processor, const MeshShader& shader, const DLoD& lod, int sigma,
                           bool limit, const LevelHomes& homes) {
  const std::vector<V3> ids = node_ids(lod.layout(sigma).num_nodes);
  MaskTable table;
  table.begin.push_back(0);
  SdcMask masks[3];
  Terms<1> step;
  Terms<3> projection;
  const auto interpolate = [&](uint32_t target, V3 p, V3 q) {  // adaptive: copy_edge's and copied nodes
    if (node_of(p) == node_of(q)) step.add(p, 0, 1.0f);
    else step.add(p, 0, 0.5f), step.add(q, 0, 0.5f);
    step.append_to(table, target);
  };
  const auto visit = [&](uint32_t target, const VertexDisk* v, const EdgeDisk* e) {
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
    if (v && !shader.has_mask(*v)) {
      probe(*v, [&](const VertexDisk& d) { return shader.vertex_vertex(d); }, step);
    } else if (v) {
      shader.vertex_mask(*v, masks[0]);
      for_each_term(masks[0], *v, [&](V3 p, float w) { step.add(p, 0, w); });
    } else if (!shader.has_mask(*e)) {
      probe(*e, [&](const EdgeDisk& d) { return shader.edge_vertex(d); }, step);
    } else {
      shader.edge_mask(*e, masks[0]);
      for_each_term(masks[0], *e, [&](V3 p, float w) { step.add(p, 0, w); });
    }
    step.append_to(table, target);
  };
  if (lod.adaptive()) processor.adaptive_shader_disks(sigma, ids.data(), limit, homes, visit, interpolate);
  else processor.shader_disks(sigma, ids.data(), limit, visit);
  return table;
}

}  // namespace sdb::mipgh
