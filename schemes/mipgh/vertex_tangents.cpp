#include "schemes/mipgh/vertex_tangents.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "schemes/mipgh/mask_table.h"
#include "schemes/mipgh/processor.h"
#include "schemes/mipgh/shader.h"

namespace sdb::mipgh {
namespace {

// A disk's slots: the centre 0, edge i's far end 1 + i, face i's opposite corner 1 + edges + i
// (quads only; a triangle's is the centre, as gather_vertex has it).
int slots(const VertexDisk& d, bool quads) { return 1 + d.edges + (quads ? d.faces : 0); }

// The disk with each node replaced by its slot's number (x), so that a mask's terms name slots.
VertexDisk numbered(const VertexDisk& d, bool quads) {
  VertexDisk n = d;
  n.c = {0, 0, 0};
  for (int i = 0; i < d.edges; ++i) n.e[i] = {float(1 + i), 0, 0};
  for (int i = 0; i < d.faces; ++i) n.d[i] = quads ? V3{float(1 + d.edges + i), 0, 0} : n.c;
  return n;
}

// Row r of the ring's subdivision matrix at this level: slot r one level down as weights on the
// slots here, by the shader's own masks (Sdc's, with the disk's tags).
using Row = std::vector<double>;
std::vector<Row> ring_rules(const MeshShader& shader, const VertexDisk& disk, const std::vector<float>& far_half,
                            bool quads) {
  const int size = slots(disk, quads);
  const VertexDisk n = numbered(disk, quads);
  std::vector<Row> m(size, Row(size, 0.0));
  SdcMask mask;
  shader.vertex_mask(disk, mask);
  for_each_term(mask, n, [&](V3 p, float w) { m[0][int(p.x)] += w; });
  for (int i = 0; i < disk.edges; ++i) {
    EdgeDisk e;
    e.v0 = n.c, e.v1 = n.e[i], e.faces = 0;
    // face i lies between edges i and i + 1, face i - 1 between i - 1 and i (a boundary's first
    // and last edge have one)
    auto add_face = [&](int f, int other_edge) {
      e.face_size[e.faces] = quads ? 4 : 3;
      e.f[e.faces][0] = n.e[other_edge], e.f[e.faces][1] = n.d[f];
      ++e.faces;
    };
    if (i < disk.faces) add_face(i, (i + 1) % disk.edges);
    if (disk.edges == disk.faces || i > 0) add_face((i + disk.faces - 1) % disk.faces, (i + disk.edges - 1) % disk.edges);
    e.sharpness = disk.edge_sharpness[i];
    e.child_sharpness[0] = disk.child_edge_sharpness[i], e.child_sharpness[1] = far_half[i];
    shader.edge_mask(e, mask);
    for_each_term(mask, e, [&](V3 p, float w) { m[1 + i][int(p.x)] += w; });
  }
  for (int f = 0; quads && f < disk.faces; ++f)
    for (int s : {0, 1 + f, 1 + disk.edges + f, 1 + (f + 1) % disk.edges}) m[1 + disk.edges + f][s] += 0.25;
  return m;
}

// What identifies a vertex's tangents on level 0: its disks' kinds and tags at every level.
void append_key(std::vector<float>& key, const VertexDisk& d, const std::vector<float>& far_half) {
  key.insert(key.end(), {float(d.edges), float(d.faces), d.sharpness, d.child_sharpness});
  for (int i = 0; i < d.faces; ++i) key.push_back(d.face_size[i]);
  for (int i = 0; i < d.edges; ++i) key.insert(key.end(), {d.edge_sharpness[i], d.child_edge_sharpness[i], far_half[i]});
}

}  // namespace

V3 BaseTangents::normal(int v, const V3* base) const {
  DoubleSum a, b;
  const V3 c = base[v];
  for (uint32_t k = begin[size_t(v)]; k < begin[size_t(v) + 1]; ++k) {
    const V3 p = base[node[k]] - c;
    a.add(t1[k], p), b.add(t2[k], p);
  }
  // The cross product in double: the tangents' components are not rounded to float first.
  const double n[3] = {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
  const double l = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (!(l > 0)) return {0, 0, 0};
  return {float(n[0] / l), float(n[1] / l), float(n[2] / l)};
}

BaseTangents compose_base_tangents(const MeshProcessor& processor, const MeshShader& shader,
                                   std::vector<uint8_t> levels) {
  const int num_vertices = int(levels.size());
  BaseTangents out;
  out.level = std::move(levels);
  out.begin.assign(1, 0);
  const std::vector<V3> ids = node_ids(uint32_t(num_vertices));  // level 0's nodes are the input's vertices
  const int deepest = num_vertices ? *std::max_element(out.level.begin(), out.level.end()) : 0;
  std::vector<VertexDisk> disks(deepest + 1);
  std::vector<std::vector<float>> far(deepest + 1);
  struct Weights {
    std::vector<double> t1, t2;  // on the level-0 disk's slots; empty: none
  };
  std::map<std::vector<float>, Weights> cache;
  for (int v = 0; v < num_vertices; ++v) {
    Weights w;
    const int level = out.level[size_t(v)];
    if (processor.vertex_has_disk(v)) {
      std::vector<float> key{float(level)};
      for (int s = 0; s <= level; ++s) {
        processor.gather_vertex(s, v, s == 0 ? ids.data() : nullptr, disks[s], &far[s]);
        append_key(key, disks[s], far[s]);
      }
      key.push_back(float(disks[0].sided));
      bool quads = true, triangles = true;
      for (int i = 0; i < disks[0].faces; ++i) quads &= disks[0].face_size[i] == 4, triangles &= disks[0].face_size[i] == 3;
      auto [it, fresh] = cache.try_emplace(key);
      if (fresh && (quads || triangles)) {
        // The level's tangent masks on its disk's slots, then back through each level's rules.
        SdcMask pos, m1, m2;
        shader.limit_masks(disks[level], pos, m1, m2);
        const VertexDisk n = numbered(disks[level], quads);
        std::vector<double> a(slots(n, quads), 0.0), b = a;
        for_each_term(m1, n, [&](V3 p, float x) { a[int(p.x)] += x; });
        for_each_term(m2, n, [&](V3 p, float x) { b[int(p.x)] += x; });
        for (int s = level - 1; s >= 0; --s) {
          const std::vector<Row> m = ring_rules(shader, disks[s], far[s], quads);
          std::vector<double> pa(m.size(), 0.0), pb = pa;
          for (size_t r = 0; r < m.size(); ++r)
            for (size_t c = 0; c < m.size(); ++c) pa[c] += a[r] * m[r][c], pb[c] += b[r] * m[r][c];
          a.swap(pa), b.swap(pb);
        }
        it->second = {a, b};
      }
      w = it->second;
    }
    if (!w.t1.empty()) {
      // Slots to nodes, a node's terms merged (a triangle's face slot is the centre).
      const VertexDisk& d = disks[0];
      std::map<uint32_t, std::pair<double, double>> terms;
      auto add = [&](V3 p, size_t slot) {
        auto& t = terms[node_of(p)];
        t.first += w.t1[slot], t.second += w.t2[slot];
      };
      add(d.c, 0);
      for (int i = 0; i < d.edges; ++i) add(d.e[i], 1 + i);
      for (size_t i = 0; 1 + d.edges + i < w.t1.size(); ++i) add(d.d[i], 1 + d.edges + i);
      for (const auto& [node, t] : terms)
        out.node.push_back(node), out.t1.push_back(float(t.first)), out.t2.push_back(float(t.second));
    }
    out.begin.push_back(uint32_t(out.node.size()));
  }
  return out;
}

}  // namespace sdb::mipgh
