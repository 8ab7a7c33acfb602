// CpatchTopology: everything the c-patch conversion needs that depends on connectivity only,
// built once in prepare(). Flat integer and float arrays, so a GPU pass can upload them as they
// are (README.md, "Data layout").
//
// Conventions (Ni et al. 2008, Figure 5 and Table 1):
// - A vertex neighbourhood of a vertex p* of valence n lists 2n mesh points p_0 .. p_{2n-1}
//   counter-clockwise: p_{2j} the direct neighbours, p_{2j+1} the diagonal ones. Sector j is the
//   quad (p*, p_{2j}, p_{2j+1}, p_{2j+2}) in its own counter-clockwise order.
// - A vertex owns n consecutive "slots" starting at first_slot[v]; slot first_slot[v] + j holds
//   the sector-j face point f_j and the edge point e_j and tangent point t_j of the edge p* p_{2j}.
// - Quad corner i of quad (q0, q1, q2, q3) is q_i; sector_slot is the slot of the sector that is
//   this quad, so f^i, e_0^i, t_0^i (edge towards q_{i+1}) live there; prev_edge_slot is the slot
//   of the edge towards q_{i-1}, holding e_1^i, t_1^i.
#pragma once

#include <cstdint>
#include <vector>

#include "harness/core/control_mesh.h"

namespace sdb::cpatch {

struct QuadCorner {
  int vertex = 0;
  int sector_slot = 0;     // f^i; e_0^i, t_0^i towards corner i+1
  int prev_edge_slot = 0;  // e_1^i, t_1^i towards corner i-1
};

// Per-valence constants of Tables 1 and 2, computed in double and rounded once.
struct ValenceConstants {
  float cos_n = 0.0f;          // c = cos(2 pi / n)
  float sin_n = 0.0f;          // s = sin(2 pi / n)
  float sigma = 0.0f;          // subdominant eigenvalue of Catmull-Clark
  float tangent_scale = 0.0f;  // 1 / (n sigma), Table 1's projection factor
  float limit_scale = 0.0f;    // 1 / (n (n + 5)), the limit-point stencil's normaliser
  int trig_offset = 0;         // cos/sin(2 pi j / n) for j = 0..n-1 at trig_cos/sin[offset + j]
};

// The five Table 2 weights of one c-patch corner i; they depend on the valences n_i and n_{i+1}.
struct CpatchCornerWeights {
  float a_i = 0.0f;     // (1 + c^i) / 4        in b211^i
  float b_next = 0.0f;  // (1 - c^{i+1}) / 8    in b211^i
  float a_next = 0.0f;  // (1 + c^{i+1}) / 4    in b121^i
  float b_i = 0.0f;     // (1 - c^i) / 8        in b121^i
  float k = 0.0f;       // 3 / (4 (s^i + s^{i+1})), in both
};

struct CpatchTopology {
  int num_vertices = 0;
  int num_quads = 0;
  std::vector<int> quad_vertices;  // 4 per quad, as in the mesh

  // Vertex neighbourhoods.
  std::vector<int> first_slot;  // num_vertices + 1 prefix sums of valences
  std::vector<int> ring;        // 2 per slot: p_{2j}, p_{2j+1}
  std::vector<int> valence;     // per vertex

  // Per valence (index n, up to max_valence).
  int max_valence = 0;
  std::vector<ValenceConstants> valence_constants;
  std::vector<float> trig_cos, trig_sin;

  std::vector<QuadCorner> corners;     // 4 per quad
  std::vector<uint8_t> extraordinary;  // per quad: 1 when a corner has valence != 4
  // Per quad, bit k set when side k (corner k -> corner k+1) runs from the lower to the higher
  // vertex index: the canonical direction in which both quads of an edge evaluate it.
  std::vector<uint8_t> forward_sides;
  std::vector<int> ordinary_quads;       // quad indices, ascending
  std::vector<int> extraordinary_quads;  // quad indices, ascending
  std::vector<int> extraordinary_index;  // per quad: its index in extraordinary_quads, or -1
  // Per extraordinary quad (index into extraordinary_quads): its four corners' Table 2 weights.
  std::vector<CpatchCornerWeights> cpatch_weights;

  int num_slots() const { return static_cast<int>(ring.size() / 2); }
  int valence_of(int v) const { return first_slot[v + 1] - first_slot[v]; }
};

// Throws InputError when the mesh is not a closed manifold all-quad mesh whose vertices all have
// one fan of faces and valence at least 3 (accept_mesh() checks most of this before).
CpatchTopology build_topology(const ControlMesh& quads);

// Catmull-Clark's subdominant eigenvalue, Table 1: (c + 5 + sqrt((c + 9)(c + 1))) / 16.
double subdominant_eigenvalue(int n);

}  // namespace sdb::cpatch
