// The levels of the D-atlas: where every node of level sigma is stored (node-morphic storage,
// Figure 17: corners, then D-edge nodes, then D-facet interiors, so a node shared by charts has
// one slot), the D-LoD (every D-facet's row-major index array at every level, Figure 10) and the
// edge tags of every level (the crease sharpness the Catmull-Clark mesh shader reads).
#pragma once

#include <cstdint>
#include <vector>

#include <opensubdiv/far/topologyLevel.h>
#include <opensubdiv/sdc/options.h>

#include "schemes/mipgh/atlas.h"

namespace sdb::mipgh {

struct LevelLayout {
  int n = 2;  // nodes along a D-facet's side: 2^sigma + 1
  int s = 0;  // nodes strictly inside a D-edge: n - 2 (s^2 inside a D-facet)
  uint32_t edge_base = 0, facet_base = 0, num_nodes = 0;

  uint32_t edge_node(int e, int k) const { return edge_base + uint32_t(e) * s + k; }
  uint32_t interior(int f) const { return facet_base + uint32_t(f) * s * s; }
};

LevelLayout level_layout(const DAtlas& atlas, int sigma);
// Nodes at level sigma, in double: for size checks before anything is allocated.
double node_count(const DAtlas& atlas, int sigma);

// Row-major (row i, column j) <-> (along a, depth b) on side k: side k's frame has a = 0 at
// corner k, a = n - 1 at corner k + 1, b counting into the facet.
inline int side_offset(int side, int n, int a, int b) {
  switch (side & 3) {
    case 0: return b * n + a;
    case 1: return a * n + (n - 1 - b);
    case 2: return (n - 1 - b) * n + (n - 1 - a);
    default: return (n - 1 - a) * n + b;
  }
}

class DLoD {
 public:
  DLoD(const DAtlas& atlas, int depth);
  const LevelLayout& layout(int sigma) const { return layouts_[sigma]; }
  // D-facet f's n x n node indices at level sigma.
  const uint32_t* facet(int sigma, int f) const {
    const int n = layouts_[sigma].n;
    return facets_[sigma].data() + size_t(f) * n * n;
  }
  int depth() const { return static_cast<int>(layouts_.size()) - 1; }

 private:
  std::vector<LevelLayout> layouts_;
  std::vector<std::vector<uint32_t>> facets_;
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
