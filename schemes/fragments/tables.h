// Pattern tables (the poster's Figure 9): for every slot of a fragment's net at level d + 1, the
// slots of level d (and, for Catmull-Clark, the face points of level d + 1) it is made from, and
// its rule with the rule's weights. One generic kernel (kernel.h) applies them and knows no
// topology. Slots are laid out face points, edge points, vertex points, so a level is three
// branch-free loops. Tables are made once per fragment shape and depth, in prepare.
//
// Every rule is written so that a point shared by fragments comes out bit-identical in each of
// them (the poster's symmetric evaluation, Figures 10-12): equal weights are applied to sums of
// pairs, sums over a vertex's ring do not depend on where the ring starts (kernel.h), so the
// different orders in which two fragments meet a point's neighbours give the same float sums.
#pragma once

#include <cstdint>
#include <vector>

#include "harness/core/control_mesh.h"
#include "schemes/fragments/net.h"

namespace sdb::fragments {

// Catmull-Clark face point of a quad: ((a + c) + (b + d)) / 4, from level d.
struct FaceRule {
  uint32_t a, b, c, d;
};

// wv (v0 + v1) + wf (f0 + f1): v from level d; f the child face points (Catmull-Clark, level
// d + 1) or the opposite vertices (Loop, level d). Creases and boundaries: wf = 0, and f0 f1 are
// not read; fractional sharpness: Sdc's blend of the two.
struct EdgeRule {
  uint32_t v0, v1, f0, f1;
  float wv, wf;
};

// wv c + wc (p0 + p1) + we sum(e) + wf sum(f): c the vertex, p0 p1 its crease neighbours, e the
// ring's vertices (num_e of them from `ring`), f the face points or, for the limit, the vertices
// opposite in each face (num_f after them). Smooth, crease, corner, dart and Sdc's blends
// between rules all take this form.
struct VertexRule {
  uint32_t centre, p0, p1, ring;
  uint16_t num_e, num_f;
  float wv, wc, we, wf;
};

struct LevelTable {
  uint32_t num_slots = 0;
  std::vector<FaceRule> faces;       // slots [0, faces)
  std::vector<EdgeRule> edges;       // then these
  std::vector<VertexRule> vertices;  // then these
  std::vector<uint32_t> ring;
};

// Limit projection of the last level's owned vertices: position by a VertexRule (symmetric too),
// the two tangents as plain weighted sums (normals need not be bit-identical to be watertight),
// one pair per vertex and side of a crease or corner.
struct LimitTable {
  std::vector<VertexRule> position;
  std::vector<uint32_t> ring;
  // Position entry i, where Far's masks are not exact (a dart), when stencil[i] >= 0: the weighted
  // sum, in this order, of stencil_slot[stencil_begin[stencil[i]] .. stencil_begin[stencil[i] + 1]).
  std::vector<int32_t> stencil;
  std::vector<uint32_t> stencil_begin = {0};
  std::vector<uint32_t> stencil_slot;
  std::vector<float> stencil_w;
  // Tangent entry i: a regular vertex (smooth, interior, valence 4 or Loop's 6) when regular[i] >= 0,
  // whose centre, ring and opposite vertices are regular_slots[regular[i] * regular_size ...] and
  // whose tangents have Sdc's regular weights (kernel.cpp); otherwise tangent_begin[i] .. [i + 1)
  // of the three lists below.
  std::vector<int32_t> regular;
  int regular_size = 0;
  std::vector<uint32_t> regular_slots;
  std::vector<uint32_t> tangent_begin;
  std::vector<uint32_t> tangent_slot;
  std::vector<float> tangent_w1, tangent_w2;
  // The same tangents as weights on the fragment's level-0 slots (net_tangents.cpp), where the
  // shape has them: entry i's first tangent is net_tangents[2 i net_size ...], its second the
  // net_size after. Applied to the control points relative to the first, they keep float's
  // precision at any depth; from the last level's points they lose a bit a level (README.md).
  uint32_t net_size = 0;
  std::vector<float> net_tangents;
  // A Catmull-Clark facet patch whose face and 1-ring are regular is a bicubic B-spline patch: its
  // tangents at grid point (i, j) are sum B'_a(u_i) B_b(v_j) P_ab and sum B_a(u_i) B'_b(v_j) P_ab,
  // a quarter of the work of net_tangents, which they equal (checked in prepare). Where present:
  // the 16 level-0 slots of P_ab at [4 a + b], and per grid index k the basis at k / 2^depth,
  // B_0..B_3 then B'_0..B'_3. Entries are in block order.
  std::vector<uint32_t> bicubic_slots;
  std::vector<float> bicubic_basis;
};

struct ShapeTables {
  int depth = 0;  // refined to; the output's depth may be lower (surface.h)
  uint32_t num_slots0 = 0;
  uint32_t max_slots = 0;          // largest level, for scratch buffers
  std::vector<LevelTable> levels;  // levels[d - 1] makes level d from level d - 1
  LimitTable limit;
  // Per owned face, per vertex of its output block (block_size(), ptex grid order), the limit
  // position entry and the tangent entry it takes.
  std::vector<uint32_t> block, block_normal;
  bool block_in_order = false;  // block[i] = block_normal[i] = i: a fragment of one face
};

// Vertices per owned face at depth d: (2^d + 1)^2 for a quad, (2^d + 1)(2^d + 2) / 2 for a
// triangle; and its triangles in ptex grid order, indices within the block.
int block_size(SubdivisionRule rule, int depth);
std::vector<uint32_t> block_triangles(SubdivisionRule rule, int depth);
// Index of grid point (i, j) (u = i / 2^d, v = j / 2^d) in a block.
int block_index(SubdivisionRule rule, int depth, int i, int j);

// Refines the net with OpenSubdiv's topology refiner to `depth` (topology and sharpness only)
// and asks Sdc for each needed point's mask; the output blocks take the points of that level
// that lie on the grid of `out_depth` (<= depth; -1: the same). Throws Unsupported where a mask
// does not have the symmetric form above.
ShapeTables build_tables(const LocalNet& net, SubdivisionRule rule, int depth, int out_depth = -1);

}  // namespace sdb::fragments
