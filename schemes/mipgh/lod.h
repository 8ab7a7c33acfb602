// The levels of the D-atlas: where every node of level sigma is stored (node-morphic storage,
// Figure 17: corners, then D-edge nodes, then D-facet interiors, so a node shared by charts has
// one slot), the D-LoD (every D-facet's row-major index array at every level, Figure 10) and the
// edge tags of every level (the crease sharpness the Catmull-Clark mesh shader reads).
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include <opensubdiv/far/topologyLevel.h>
#include <opensubdiv/sdc/options.h>

#include "schemes/mipgh/atlas.h"

namespace sdb::mipgh {

struct LevelLayout {
  int n = 2;  // nodes along a D-facet's side: 2^sigma + 1
  int s = 0;  // nodes strictly inside a D-edge: n - 2 (s^2 inside a quad, s(s-1)/2 a triangle)
  uint32_t edge_base = 0, facet_base = 0, num_nodes = 0;
  const int32_t* quads_before = nullptr;  // the atlas's
  // An adaptive level (DLoD's labels) stores only the D-edges and D-facets it holds, each at its
  // own first node: these tables, owned by the DLoD (null: every one, in order).
  const uint32_t* edge_first = nullptr;
  const uint32_t* facet_first = nullptr;

  uint32_t edge_node(int e, int k) const { return (edge_first ? edge_first[e] : edge_base + uint32_t(e) * s) + k; }
  uint32_t interior(int f) const {
    if (facet_first) return facet_first[f];
    const uint32_t q = quads_before[f], t = uint32_t(f) - q;
    return facet_base + q * s * s + t * (s * (s - 1) / 2);
  }
};

// A triangular D-facet's row-major array (Figure 10): row i holds n - i nodes.
inline int tri_offset(int n, int i, int j) { return i * n - i * (i - 1) / 2 + j; }

LevelLayout level_layout(const DAtlas& atlas, int sigma);
// Nodes at level sigma, in double: for size checks before anything is allocated.
double node_count(const DAtlas& atlas, int sigma);

// (along a, depth b) on side k -> (row i, column j) of a D-facet's array. Side k's frame has a = 0
// at corner k, a = n - 1 at corner k + 1, b counting into the facet. A quad's rows run along side
// 0 from corner 0; a triangle's too (row i holds n - i nodes, column j along side 0, row along
// side 2 back to corner 0), and its frames are used at b = 0 and 1 only: the row one in from a
// side has n - 1 nodes, node a of it next to the side's nodes a and a + 1 (the strip a D-edge
// visit reads).
struct RowColumn {
  int i, j;
};
inline RowColumn side_ij(int size, int side, int n, int a, int b) {
  if (size == 4) switch (side) {
      case 0: return {b, a};
      case 1: return {a, n - 1 - b};
      case 2: return {n - 1 - b, n - 1 - a};
      default: return {n - 1 - a, b};
    }
  switch (side) {
    case 0: return {b, a};
    case 1: return {a, n - 1 - b - a};
    default: return {n - 1 - b - a, b};
  }
}
inline int facet_offset(int size, int n, RowColumn p) { return size == 4 ? p.i * n + p.j : tri_offset(n, p.i, p.j); }
inline int facet_side_offset(int size, int side, int n, int a, int b) {
  return facet_offset(size, n, side_ij(size, side, n, a, b));
}
inline int side_offset(int side, int n, int a, int b) { return facet_side_offset(4, side, n, a, b); }

class DLoD {
 public:
  // Uniform: every D-facet refined to `depth`.
  DLoD(const DAtlas& atlas, int depth);
  // Adaptive refinement (Figures 13, 14): D-facet f refined to labels[f] (<= depth). Level sigma
  // holds the D-facets refined to sigma or beyond and, as the auxiliary layer, the D-facets that
  // share a D-vertex with one of them, whose nodes near it the refined facets' 1-disks read; the
  // D-edges of those; no other D-facet's nodes are visited or allocated there. Departure: the
  // auxiliary D-facets are refined whole, not as one row of nodes, so that their visit is the
  // uniform one (the nodes a refined D-facet reads come out bit for bit as uniform refinement's).
  DLoD(const DAtlas& atlas, int depth, std::vector<uint8_t> labels);
  DLoD(const DLoD&) = delete;
  DLoD& operator=(const DLoD&) = delete;

  const LevelLayout& layout(int sigma) const { return layouts_[sigma]; }
  // D-facet f's node indices at level sigma: n x n for a quad, n(n+1)/2 for a triangle. Only for
  // a D-facet the level holds.
  const uint32_t* facet(int sigma, int f) const { return facets_[sigma].data() + facet_at_[sigma][f]; }
  int depth() const { return static_cast<int>(layouts_.size()) - 1; }
  // The most nodes any of levels 0..upto holds (uniform: level upto's; adaptive: any level's).
  uint32_t most_nodes(int upto) const {
    uint32_t most = 0;
    for (int sigma = 0; sigma <= upto; ++sigma) most = std::max(most, layouts_[sigma].num_nodes);
    return most;
  }

  bool adaptive() const { return !labels_.empty(); }
  int label(int f) const { return adaptive() ? labels_[f] : depth(); }
  // Whether level sigma holds D-facet f (refined there or auxiliary).
  bool holds_facet(int sigma, int f) const { return !adaptive() || facet_first_[sigma][f] != kAbsent; }
  // Adaptive: the D-facets and D-edges level sigma holds, in order.
  const std::vector<int32_t>& facets_held(int sigma) const { return facets_held_[sigma]; }
  const std::vector<int32_t>& edges_held(int sigma) const { return edges_held_[sigma]; }

  static constexpr uint32_t kAbsent = 0xffffffffu;

 private:
  void lay_out(const DAtlas& atlas, int sigma, const std::vector<uint8_t>& held);

  std::vector<uint8_t> labels_;
  std::vector<LevelLayout> layouts_;
  std::vector<std::vector<uint32_t>> facets_;
  std::vector<std::vector<size_t>> facet_at_;
  std::vector<std::vector<uint32_t>> edge_first_, facet_first_;
  std::vector<std::vector<int32_t>> facets_held_, edges_held_;
};

// Adaptive output: the D-facets whose interiors, the D-edges whose nodes and the D-vertices whose
// output comes from one level (its home: the finest level that draws them, primitives.h).
struct LevelHomes {
  std::vector<int32_t> facets, edges, vertices;
};

// Crease sharpness along D-edges and at D-vertices, every level. Edges inside a D-facet are born
// at a refinement and are never sharp, so only D-edge micro-edges carry tags. Departure from the
// paper's micro-facet-morphic list (Figure 19: two values per micro-facet corner): the same values
// stored once per D-edge micro-edge, in the major halfedge's direction, and only for D-edges that
// are sharp at level 0 (boundaries are: Sdc sharpens them).
struct EdgeTags {
  std::vector<int32_t> slot;                // per D-edge: -1 smooth at every level, else its row
  std::vector<std::vector<float>> edge;     // per level: 2^sigma values per tagged D-edge
  std::vector<std::vector<float>> vertex;   // per level: per D-vertex
  bool any = false;

  float micro_edge(int sigma, int e, int t) const {
    return slot[e] < 0 ? 0.0f : edge[sigma][(size_t(slot[e]) << sigma) + t];
  }
};

// From Far's level 0 (boundaries, creases and corners as Far reads the mesh), refined with Sdc's
// Crease rules (uniform decrement or Chaikin) as Far refines them.
EdgeTags build_tags(const DAtlas& atlas, const OpenSubdiv::Far::TopologyLevel& base,
                    const OpenSubdiv::Sdc::Options& options, int depth);

}  // namespace sdb::mipgh
