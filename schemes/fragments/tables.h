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
  // Per output block (owned face), the level-0 slots some of its entries' net tangents weigh
  // (net_support[net_support_begin[b] .. [b + 1]), slot 0 left out: the first control point is
  // the origin): a face's limit depends on its 1-ring alone, 13 of a valence-7 vertex patch's 22
  // control points, so the CPU kernel skips the zeros.
  std::vector<uint32_t> net_support_begin, net_support;
  // Per tangent entry: its vertex is a control vertex's (level 0's, refined on). A fragment whose
  // shape it has alone (the CPU's one-lane kernel) reads only these entries' net tangents, where a
  // low-valence ring shrinks fastest; the rest it takes from a second refinement of its net
  // relative to its first control point, which holds float's precision as well without reading
  // 2 x net_size weights a vertex from memory (kernel.h).
  std::vector<char> at_control_vertex;
  // Where a one-face block's limit is one polynomial in (u, v) (a regular patch: bicubic for
  // Catmull-Clark, of total degree 4 for Loop), its monomials u^a v^b (a-major, b ascending: for
  // Loop a + b <= 4, 15 of them; bicubic a, b <= 3, 16) with their coefficients as weights on
  // the net (patch_weights, monomials x net_size), fitted to the limit
  // positions in prepare and kept where they reproduce them to 1e-9: the tangents are its
  // derivatives d/du and d/dv (ptex orientation), evaluated row by row with Horner's rule, a
  // fraction of net_tangents' work. Row j of `patch_segments` holds vertices (i, j), i = 0 .. s
  // (Loop: s - j).
  int patch_segments = 0;
  bool patch_triangle = false;
  std::vector<float> patch_weights;
};

struct ShapeTables {
  int depth = 0;  // refined to; the output's depth may be lower (surface.h)
  uint32_t num_slots0 = 0;
  uint32_t max_slots = 0;          // largest level, for scratch buffers
  std::vector<LevelTable> levels;  // levels[d - 1] makes level d from level d - 1
  LimitTable limit;
  // The limit's entries are the output blocks' vertices, one block per owned face (block_size(),
  // ptex grid order) after another.
  int owned_faces = 0;
  size_t block_vertices() const { return limit.position.size(); }
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
