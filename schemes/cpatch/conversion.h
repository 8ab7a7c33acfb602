// CpatchConverter: Ni, Yeo, Myles, Goel, Peters 2008, "GPU Smoothing of Quad Meshes", Section 2.
// Stage 1 (per vertex, Table 1): limit point v, face points f_j, edge points e_j and tangent
// points t_j (the e_j projected into a common tangent plane). Stage 2 (per quad): a bicubic Bezier
// patch for an ordinary quad (Figure 6), a c-patch (Table 2, equation (5)) for an extraordinary one.
// Both stages read only the current control positions and the CpatchTopology; they are the
// per-frame part of the scheme and what the GPU passes mirror (README.md).
#pragma once

#include <array>
#include <vector>

#include "schemes/cpatch/topology.h"
#include "schemes/cpatch/vec3.h"

namespace sdb::cpatch {

// Stage 1 output. Every point is stored relative to the control vertex p* it was computed at
// (limit[v] = v - p*, face/edge/tangent[slot] = point - p* of the slot's vertex): float rounding
// then scales with the neighbourhood's size instead of the coordinates' magnitude, which on fine
// meshes far from the origin is the difference between Lemma 1 holding to 1e-6 degrees or to
// 0.1 degrees (README.md, "Float precision"). limit_absolute[v] = p* + limit[v], rounded once.
struct VertexPoints {
  std::vector<Vec3f> limit;           // v - p*
  std::vector<Vec3f> limit_absolute;  // v
  std::vector<Vec3f> face;            // f_j - p*
  std::vector<Vec3f> edge;            // e_j - p*
  std::vector<Vec3f> tangent;         // t_j - p*
  void resize(const CpatchTopology& t);
};

// A patch record: 28 Vec3f per quad, seven per corner i (corner-major), the paper's stream-out of
// pass 1 (Table 3) plus the corner positions that anchor the relative coordinates:
//   kP    p*_i, the control vertex at corner i (absolute)
//   kV    v^i - p*_i
//   kT0   t_0^i - p*_i (towards corner i+1)
//   kT1   t_1^i - p*_i (towards corner i-1)
//   kX0.. interior coefficients relative to p*_0, the patch origin: for a bicubic patch f^i
//         (the inner Bezier point at corner i; kX1, kX2 unused), for a c-patch b^i_211, b^i_121,
//         b^i_112.
// The quad side i -> i+1 is the cubic (v^i, t_0^i, t_1^{i+1}, v^{i+1}) for both kinds, built from
// per-vertex data only, which is what makes borders agree bit for bit.
constexpr int kRecordSize = 28;
enum RecordEntry { kP = 0, kV = 1, kT0 = 2, kT1 = 3, kX0 = 4, kX1 = 5, kX2 = 6 };
constexpr RecordEntry kF = kX0, kB211 = kX0, kB121 = kX1, kB112 = kX2;
inline constexpr int record_index(int corner, RecordEntry e) { return 7 * corner + e; }
using PatchRecord = std::array<Vec3f, kRecordSize>;

// Table 1's projection of the edge points e_0..e_{n-1} around v into the tangent plane:
// t_j = v + 1/(n sigma_n) sum_l cos(2 pi (j - l) / n) (e_l - v), written as
// v + 1/(n sigma_n) (cos_j A + sin_j B) with A = sum_l cos_l (e_l - v), B = sum_l sin_l (e_l - v).
void project_tangents(Vec3f v, const Vec3f* e, int n, const ValenceConstants& k, const float* cos_j, const float* sin_j,
                      Vec3f* t);

// One extraordinary quad's corner data, as Table 2 reads it.
struct CpatchCornerInput {
  Vec3f v, t0, t1;  // limit point, tangent points towards corner i+1 and i-1
  Vec3f f;          // face point of this quad's sector
  Vec3f e0, e1;     // edge points towards corner i+1 and i-1
};

struct CpatchInterior {
  Vec3f b211[4], b121[4], b112[4];
};

// Table 2 with the b112 formula corrected (README.md, "Corrections"): b211, b121 from the corner
// data, b112 solving equation (5) with the average of the b112 equal to g(1/2, 1/2).
CpatchInterior cpatch_interior(const CpatchCornerInput c[4], const CpatchCornerWeights w[4]);

class CpatchConverter {
 public:
  explicit CpatchConverter(const CpatchTopology& topology) : t_(topology) {}

  // Table 1 for vertices [begin, end).
  void convert_vertices(const Vec3f* positions, int begin, int end, VertexPoints& out) const;
  // Figure 6: the record of ordinary quad `quad`.
  void build_bicubic(const Vec3f* positions, const VertexPoints& points, int quad, Vec3f* record) const;
  // Table 2: the record of the `index`-th extraordinary quad (topology.extraordinary_quads[index]).
  void build_cpatch(const Vec3f* positions, const VertexPoints& points, int index, Vec3f* record) const;
  // Either, by the quad's kind.
  void build_patch(const Vec3f* positions, const VertexPoints& points, int quad, Vec3f* record) const;

  const CpatchTopology& topology() const { return t_; }

 private:
  void convert_vertex(const Vec3f* positions, int vertex, VertexPoints& out) const;
  void write_corners(const Vec3f* positions, const VertexPoints& points, int quad, Vec3f* record) const;
  const CpatchTopology& t_;
};

}  // namespace sdb::cpatch
