#include "schemes/mipgh/lod.h"

#include <opensubdiv/sdc/crease.h>

#include <algorithm>
#include <cmath>
#include <utility>

namespace sdb::mipgh {

namespace Sdc = OpenSubdiv::Sdc;

LevelLayout level_layout(const DAtlas& atlas, int sigma) {
  LevelLayout l;
  l.n = (1 << sigma) + 1;
  l.s = l.n - 2;
  l.edge_base = static_cast<uint32_t>(atlas.num_vertices);
  l.facet_base = l.edge_base + uint32_t(atlas.num_edges()) * l.s;
  l.quads_before = atlas.quads_before.data();
  l.num_nodes = l.interior(atlas.num_facets());
  return l;
}

double node_count(const DAtlas& atlas, int sigma) {
  const double s = std::ldexp(1.0, sigma) - 1, quads = atlas.quads_before.back();
  return atlas.num_vertices + atlas.num_edges() * s + quads * s * s + (atlas.num_facets() - quads) * s * (s - 1) / 2;
}

DLoD::DLoD(const DAtlas& atlas, int depth) {
  const std::vector<uint8_t> all(atlas.num_facets(), 1);
  for (int sigma = 0; sigma <= depth; ++sigma) lay_out(atlas, sigma, all);
}

DLoD::DLoD(const DAtlas& atlas, int depth, std::vector<uint8_t> labels) : labels_(std::move(labels)) {
  std::vector<uint8_t> near(atlas.num_vertices), held(atlas.num_facets());
  for (int sigma = 0; sigma <= depth; ++sigma) {
    std::fill(near.begin(), near.end(), 0);
    for (int f = 0; f < atlas.num_facets(); ++f)
      if (labels_[f] >= sigma)
        for (int k = 0; k < atlas.facet_size[f]; ++k) near[atlas.facet_corners[f][k]] = 1;
    for (int f = 0; f < atlas.num_facets(); ++f) {
      held[f] = 0;
      for (int k = 0; k < atlas.facet_size[f]; ++k) held[f] |= near[atlas.facet_corners[f][k]];
    }
    lay_out(atlas, sigma, held);
  }
}

void DLoD::lay_out(const DAtlas& atlas, int sigma, const std::vector<uint8_t>& held) {
  LevelLayout l = level_layout(atlas, sigma);
  const int n = l.n, s = l.s, F = atlas.num_facets();
  auto interior_nodes = [&](int f) { return uint32_t(atlas.facet_size[f] == 4 ? s * s : s * (s - 1) / 2); };
  std::vector<uint32_t> edge_first, facet_first;
  std::vector<int32_t> facets_held, edges_held;
  if (adaptive()) {
    edge_first.assign(atlas.num_edges(), kAbsent), facet_first.assign(F, kAbsent);
    uint32_t next = uint32_t(atlas.num_vertices);
    for (int e = 0; e < atlas.num_edges(); ++e) {
      const DEdge& d = atlas.edges[e];
      if (!held[d.major.facet] && (d.minor.null() || !held[d.minor.facet])) continue;
      edge_first[e] = next, next += uint32_t(s);
      edges_held.push_back(e);
    }
    l.facet_base = next;
    for (int f = 0; f < F; ++f)
      if (held[f]) facet_first[f] = next, next += interior_nodes(f), facets_held.push_back(f);
    l.num_nodes = next;
    // moved into edge_first_ and facet_first_ below: a moved vector keeps its buffer
    l.edge_first = edge_first.data(), l.facet_first = facet_first.data();
  }
  layouts_.push_back(l);
  std::vector<size_t> at(F, 0);
  size_t words = 0;
  for (int f = 0; f < F; ++f) {
    at[f] = words;
    if (held[f]) words += atlas.facet_size[f] == 4 ? size_t(n) * n : size_t(n) * (n + 1) / 2;
  }
  std::vector<uint32_t> index(words);
  for (int f = 0; f < F; ++f) {
    if (!held[f]) continue;
    uint32_t* d = index.data() + at[f];
    const int size = atlas.facet_size[f];
    for (int k = 0; k < size; ++k) {
      d[facet_side_offset(size, k, n, 0, 0)] = static_cast<uint32_t>(atlas.facet_corners[f][k]);
      const int e = atlas.facet_edges[f][k];
      const bool minor = atlas.facet_side_minor[f][k];
      for (int a = 1; a <= s; ++a) d[facet_side_offset(size, k, n, a, 0)] = l.edge_node(e, minor ? s - a : a - 1);
    }
    uint32_t inside = l.interior(f);  // row-major, as the D-facet visit writes them
    for (int i = 1; i <= s; ++i)
      for (int j = 1; size == 4 ? j <= s : i + j <= s; ++j) d[size == 4 ? i * n + j : tri_offset(n, i, j)] = inside++;
  }
  facets_.push_back(std::move(index));
  facet_at_.push_back(std::move(at));
  edge_first_.push_back(std::move(edge_first));
  facet_first_.push_back(std::move(facet_first));
  facets_held_.push_back(std::move(facets_held));
  edges_held_.push_back(std::move(edges_held));
}

namespace {

// The sharpness of every D-edge micro-edge meeting D-vertex v at level sigma (the one next to v).
void sharpness_around(const DAtlas& atlas, const EdgeTags& tags, int sigma, int v, std::vector<float>& out) {
  out.clear();
  const int last = (1 << sigma) - 1;
  auto near_v = [&](int f, int side, bool v_is_side_start) {
    const int e = atlas.facet_edges[f][side];
    const bool minor = atlas.facet_side_minor[f][side];
    // v at the side's start is the major's start exactly when the side is the major halfedge
    return tags.micro_edge(sigma, e, (v_is_side_start != minor) ? 0 : last);
  };
  for (int i = atlas.ring_offsets[v]; i < atlas.ring_offsets[v + 1]; ++i) out.push_back(near_v(atlas.ring[i].facet, atlas.ring[i].side, true));
  if (atlas.vertex_boundary[v] && atlas.valence(v) > 0) {
    const HalfEdge& lastf = atlas.ring[atlas.ring_offsets[v + 1] - 1];
    out.push_back(near_v(lastf.facet, atlas.prev(lastf.facet, lastf.side), false));
  }
}

}  // namespace

EdgeTags build_tags(const DAtlas& atlas, const OpenSubdiv::Far::TopologyLevel& base, const Sdc::Options& options,
                    int depth) {
  EdgeTags t;
  t.slot.assign(atlas.num_edges(), -1);
  std::vector<float> level0;
  for (int e = 0; e < atlas.num_edges(); ++e) {
    const HalfEdge& h = atlas.edges[e].major;
    const int far = base.FindEdge(atlas.facet_corners[h.facet][h.side], atlas.facet_corners[h.facet][atlas.next(h.facet, h.side)]);
    const float s = far < 0 ? 0.0f : base.GetEdgeSharpness(far);
    if (s > 0) t.slot[e] = static_cast<int32_t>(level0.size()), level0.push_back(s);
  }
  std::vector<float> vertex0(atlas.num_vertices, 0.0f);
  for (int v = 0; v < atlas.num_vertices; ++v) vertex0[v] = base.GetVertexSharpness(v);
  t.any = !level0.empty() || std::any_of(vertex0.begin(), vertex0.end(), [](float s) { return s > 0; });
  if (!t.any) return t;
  t.edge.push_back(std::move(level0));
  t.vertex.push_back(std::move(vertex0));
  const Sdc::Crease crease(options);
  std::vector<float> around;
  for (int sigma = 0; sigma < depth; ++sigma) {
    const std::vector<float>& p = t.edge[sigma];
    std::vector<float> c(p.size() * 2);
    const int m = 1 << sigma;  // micro-edges per D-edge at sigma
    // Chaikin reads the sharp edges around the end vertex each half keeps.
    std::vector<std::vector<float>> at_vertex(atlas.num_vertices);
    if (!crease.IsUniform())
      for (int v = 0; v < atlas.num_vertices; ++v) sharpness_around(atlas, t, sigma, v, at_vertex[v]);
    for (int e = 0; e < atlas.num_edges(); ++e) {
      if (t.slot[e] < 0) continue;
      const float* pe = p.data() + (size_t(t.slot[e]) << sigma);
      float* ce = c.data() + (size_t(t.slot[e]) << (sigma + 1));
      const DEdge& d = atlas.edges[e];
      const int v0 = atlas.facet_corners[d.major.facet][d.major.side];
      const int v1 = atlas.facet_corners[d.major.facet][atlas.next(d.major.facet, d.major.side)];
      // A node inside a D-edge has 4 edges between quads, 6 between triangles (one fewer each
      // way on a boundary); only the two along the D-edge can be sharp.
      auto inner_edges = [&](const HalfEdge& h) { return h.null() ? 0 : atlas.facet_size[h.facet] == 4 ? 1 : 2; };
      const int interior_valence = 2 + inner_edges(d.major) + inner_edges(d.minor);
      for (int k = 0; k < m; ++k) {
        if (crease.IsUniform() || Sdc::Crease::IsInfinite(pe[k])) {
          ce[2 * k] = ce[2 * k + 1] = crease.SubdivideUniformSharpness(pe[k]);
          continue;
        }
        // half 2k keeps node k's end, half 2k+1 node k+1's
        for (int h = 0; h < 2; ++h) {
          const int node = k + h;
          if (node == 0 || node == m) {
            const std::vector<float>& a = at_vertex[node == 0 ? v0 : v1];
            ce[2 * k + h] = crease.SubdivideEdgeSharpnessAtVertex(pe[k], static_cast<int>(a.size()), a.data());
          } else {
            float a[6] = {pe[node - 1], pe[node], 0.0f, 0.0f, 0.0f, 0.0f};
            ce[2 * k + h] = crease.SubdivideEdgeSharpnessAtVertex(pe[k], interior_valence, a);
          }
        }
      }
    }
    t.edge.push_back(std::move(c));
    std::vector<float> cv(atlas.num_vertices);
    for (int v = 0; v < atlas.num_vertices; ++v) cv[v] = crease.SubdivideVertexSharpness(t.vertex[sigma][v]);
    t.vertex.push_back(std::move(cv));
  }
  return t;
}

}  // namespace sdb::mipgh
