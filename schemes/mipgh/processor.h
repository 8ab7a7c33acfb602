// The mesh processor (Section 3.1, Figures 7, 8, 24): one mutation step visits every node of the
// next level, D-facets, D-edges and D-vertices, gathers its 1-disk from the current level through
// the D-LoD's index arrays, and hands it to the mesh shader; the refinement itself is the next
// level's layout (lod.h), fixed in prepare. Departure in order only: the paper visits all D-facets,
// then all D-edges, then all D-vertices; here each tile of D-facets is followed by the D-edges and
// D-vertices whose last D-facet it holds, while their neighbours are still in cache. Every node is
// computed from the previous level alone, so the order changes no value. Then the limit projection, a last visit
// without refinement (Figure 24's bypassed case), and primitive compilation.
//
// Attributes are node-morphic: a node shared by D-facets has one slot, computed once, so the
// output is watertight by construction (no welding, no symmetric evaluation needed).
#pragma once

#include <functional>
#include <vector>

#include "harness/core/tessellation.h"
#include "schemes/mipgh/atlas.h"
#include "schemes/mipgh/lod.h"
#include "schemes/mipgh/shader.h"
#include "schemes/mipgh/vertex_tangents.h"

namespace sdb::mipgh {

class MeshProcessor {
 public:
  MeshProcessor(const DAtlas& atlas, const DLoD& lod, const EdgeTags& tags, const MeshShader& shader);

  // Level sigma's nodes in `src`, level sigma + 1's written to `dst`. `patches`, where given: the
  // step before a projection that takes the regular D-facets' interiors and D-edges from them
  // (project_facets, project_edge). Of those only what the projection of the D-vertices and the
  // other D-facets and D-edges reads is made: a regular D-facet's node next to each corner (a
  // D-vertex's 1-disk reaches one node in), a D-edge between two regular D-facets its node next
  // to each end (the whole D-edge where another D-facet's tile holds it); the rest (at depth 4,
  // 221 of a D-facet's 225 and 13 of a D-edge's 15) is left as it was, never read.
  void step(int sigma, const V3* src, V3* dst, bool parallel, const RegularPatches* patches = nullptr) const;
  // Limit positions and unit normals of level sigma's nodes; the positions moved by `offset` where
  // one is given (the output's origin, so that they are written once, where they end).
  // `base`, where given, takes the D-vertices' normals from level 0's nodes (vertex_tangents.h).
  void project(int sigma, const V3* src, V3* position, V3* normal, bool parallel, const V3* offset = nullptr,
               const BaseLevel* base = nullptr) const;
  // Adaptive (DLoD's labels): the limit of the nodes whose home is level sigma only: the
  // interiors of these D-facets, the nodes of these D-edges and these D-vertices.
  using Homes = LevelHomes;
  void project(int sigma, const V3* src, V3* position, V3* normal, const Homes& homes, bool parallel,
               const BaseLevel* base = nullptr) const;

  // Adjustment without refinement (Figure 24's bypassed case): every node of level sigma is
  // replaced by what `shader` makes of its 1-disk there (read from src, written to dst). Any
  // attribute of up to three floats per node; the game of life (paper/life.cpp) is one.
  using Adjustment = std::function<V3(const VertexDisk&)>;
  void adjust(int sigma, const V3* src, V3* dst, const Adjustment& shader) const;
  // The visits behind adjust: every node of level sigma with its 1-disk there (none for a node in
  // no face: a VertexDisk with no edges).
  using AdjustmentVisitor = std::function<void(uint32_t node, const VertexDisk& disk)>;
  void adjustment_disks(int sigma, const V3* src, const AdjustmentVisitor& visit) const;

  // The 1-disks the fast paths leave to the mesh shader's masks, each with the node it makes: a
  // step's (limit = false: level sigma + 1's D-vertices and the edge and vertex points of D-edges
  // that are not fast_edge) or the limit projection's (level sigma's D-vertices and such D-edges'
  // nodes). An edge point comes as `edge`, any other node as `vertex`; a node that is copied (a
  // D-vertex in no face, or joining several fans) as a VertexDisk with no edges.
  using DiskVisitor = std::function<void(uint32_t target, const VertexDisk* vertex, const EdgeDisk* edge)>;
  void shader_disks(int sigma, const V3* src, bool limit, const DiskVisitor& visit) const;
  // Adaptive (DLoD's labels), the same for what a step makes besides the fast paths: level
  // sigma + 1's held D-edges and the D-vertices, where readable as above, else interpolated as
  // copy_edge does (`interpolate(target, p, q)`: the midpoint of p and q, or p where p is q) and
  // copied; or (limit) the projection's of `homes` at level sigma.
  using Interpolation = std::function<void(uint32_t target, V3 p, V3 q)>;
  void adaptive_shader_disks(int sigma, const V3* src, bool limit, const Homes& homes, const DiskVisitor& visit,
                             const Interpolation& interpolate) const;
  // Level sigma's offsets of the nodes along each side and one in from it, for every kind of side
  // (a triangle's three, then a quad's four): (kind * 2 + depth) * n + a.
  const std::vector<int32_t>& side_row_table(int sigma) const { return side_rows_[sigma]; }
  // Whether D-edge e's nodes take the fast paths: untagged at every level, two D-facets of one kind.
  bool fast_edge(int e) const;

  // The D-facets of one tile (tile.h): a quad, or one or two triangles (second -1 where none).
  struct TileFacets {
    int32_t first, second;
  };
  // The parts of a step, public for the tests.
  void visit_facets(int sigma, TileFacets facets, const V3* src, V3* dst) const;
  // step's with `patches`: quad f's four targets next to its corners (its squares' facet points),
  // and a tag-free D-edge's between two quads next to its ends (edge points), as the full visits
  // compute them.
  void visit_facet_corners(int sigma, int f, const V3* src, V3* dst) const;
  void visit_edge_ends(int sigma, int e, const V3* src, V3* dst) const;
  void visit_edge(int sigma, int e, const V3* src, V3* dst) const;
  void visit_vertex(int sigma, int v, const V3* src, V3* dst) const;
  // Adaptive: whether level sigma holds every D-facet a D-edge's (or a D-vertex's) next nodes
  // read. Where not, the nodes lie away from every refined D-facet, no refined node reads them,
  // and the step interpolates them instead (copy_edge).
  bool edge_readable(int sigma, int e) const;
  bool vertex_readable(int sigma, int v) const;
  void copy_edge(int sigma, int e, const V3* src, V3* dst) const;
  // D-vertex v's 1-disk at level sigma (and its tags at sigma and sigma + 1); where `far_half` is
  // given, the sharpness at sigma + 1 of the half of each of its edges away from v (Sdc's edge
  // rule reads both halves under Chaikin: vertex_tangents.cpp rebuilds the edges' rules).
  void gather_vertex(int sigma, int v, const V3* src, VertexDisk& disk, std::vector<float>* far_half = nullptr) const;
  // Whether D-vertex v's limit comes from its 1-disk (not a bare vertex, nor a corner of several fans).
  bool vertex_has_disk(int v) const { return atlas_.valence(v) > 0 && atlas_.vertex_fans[v] == 1; }

 private:
  // The nodes copy_edge makes of D-edge e at level sigma + 1, each as node(target, i, j) with the
  // level-sigma nodes i and j it is the midpoint of (i == j: a copy of i).
  template <class F>
  void copied_edge_nodes(int sigma, int e, F&& node) const;
  // The 1-disk of the strip's node t on D-edge e (1 <= t <= n - 2), tags included; after
  // load_strip.
  void strip_disk(int sigma, int e, int t, VertexDisk& disk) const;
  // The 1-disk of the edge point of the strip's micro-edge t (t, t + 1); after load_strip.
  void edge_disk(int sigma, int e, int t, EdgeDisk& disk) const;
  // The D-facets' nodes at level sigma into the thread's tile, its stencil planes sized; true for
  // a quad.
  bool load_tile(int sigma, TileFacets facets, const V3* src) const;
  // Reads D-edge e's strip (processor.cpp, Strip) into the thread's scratch.
  void load_strip(int sigma, int e, const V3* src) const;
  // A fast D-edge's strip as three rows of the thread's strip tile, where the tile's stencils
  // read them along row 1 (the edge's nodes a[t]): row 2 the major side's b[t], row 0 the minor
  // side's c[t], a quad's at column t (across from a[t]), a triangle's at t + 1 (between a[t] and
  // a[t + 1]); the strip's stencil planes sized. True for quads.
  bool load_strip_rows(int sigma, int e, const V3* src) const;
  // The array offsets of the nodes along a side (depth 0) or one in from it (1), at level sigma.
  const int32_t* side_rows(int sigma, int size, int side, int depth) const;
  void project_facets(int sigma, TileFacets facets, const V3* src, V3* position, V3* normal, const V3* offset,
                      const BaseLevel* base) const;
  // The limit of D-edge e's nodes by the stencils and masks of level sigma alone; without
  // `normals` (taken from level 0 instead) the normals of a tag-free quad strip are left unwritten.
  void project_edge_nodes(int sigma, int e, const V3* src, V3* position, V3* normal, const V3* offset,
                          bool normals) const;
  void project_edge(int sigma, int e, const V3* src, V3* position, V3* normal, const V3* offset,
                    const BaseLevel* base) const;
  void project_vertex(int sigma, int v, const V3* src, V3* position, V3* normal, const V3* offset,
                      const BaseLevel* base = nullptr) const;
  void step_adaptive(int sigma, const V3* src, V3* dst, bool parallel) const;
  // tiles_, and the D-edges and D-vertices each tile's visit takes along.
  void plan_tiles();

 private:
  // shader_disks' parts: D-vertex v's node, and D-edge e's nodes.
  void vertex_shader_disk(int sigma, int v, const V3* src, bool limit, const DiskVisitor& visit) const;
  void edge_shader_disks(int sigma, int e, const V3* src, bool limit, const DiskVisitor& visit) const;

  const DAtlas& atlas_;
  const DLoD& lod_;
  const EdgeTags& tags_;
  const MeshShader& shader_;
  std::vector<int> vertex_order_;
  std::vector<TileFacets> tiles_;  // every D-facet, consecutive triangles paired
  // Items (D-edges or D-vertices) listed by the tile they are visited with.
  class PerTile {
   public:
    PerTile() = default;
    PerTile(const std::vector<int32_t>& tile_of_item, size_t tiles) : begin_(tiles + 1, 0), items_(tile_of_item.size()) {
      for (int32_t t : tile_of_item) ++begin_[size_t(t) + 1];
      for (size_t t = 0; t < tiles; ++t) begin_[t + 1] += begin_[t];
      std::vector<int32_t> next(begin_.begin(), begin_.end() - 1);
      for (size_t i = 0; i < tile_of_item.size(); ++i) items_[size_t(next[size_t(tile_of_item[i])]++)] = int32_t(i);
    }
    struct Range {
      const int32_t *b, *e;
      const int32_t* begin() const { return b; }
      const int32_t* end() const { return e; }
    };
    Range of(int tile) const { return {items_.data() + begin_[size_t(tile)], items_.data() + begin_[size_t(tile) + 1]}; }

   private:
    std::vector<int32_t> begin_, items_;
  };
  PerTile tile_edges_, tile_vertices_;
  std::vector<std::vector<int32_t>> side_rows_;
};

}  // namespace sdb::mipgh
