// Evaluation of patch records (conversion.h) on the N x N grid u_i = i / (N - 1) of a quad's
// ptex domain: (u, v) = (0,0) at corner 0, (1,0) at corner 1, (1,1) at corner 2, (0,1) at corner 3.
//
// SampleGrid holds what depends on N only (Bernstein weights of the bicubic, the c-patch's
// per-sample quartic weights grouped by triangular piece), computed once in prepare(). The per-quad
// routines work on a PatchScratch in structure-of-arrays form so the compiler vectorises across
// samples, then interleave into the Tessellation's packed float3 arrays.
//
// Borders: every quad side is evaluated by border_point() on the side's four cubic control points
// in canonical order (lower vertex index first) at the canonical sample index, and corners are
// copied from v. Both quads of an edge, bicubic or c-patch, therefore write bit-identical positions
// there (README.md, "Exact borders"). Interior samples and all normals come from the patch itself.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "harness/core/control_mesh.h"
#include "harness/core/tessellation.h"
#include "schemes/cpatch/conversion.h"
#include "schemes/cpatch/topology.h"
#include "schemes/cpatch/vec3.h"

// The hot loops are built for AVX2 and for the x86-64 baseline, picked at load time; both give
// the same bits (no fused multiply-adds). Define SDB_CPATCH_BASELINE_ONLY to build the baseline
// alone (to test it on an AVX2 machine).
#if defined(SDB_CPATCH_BASELINE_ONLY) || !defined(__x86_64__)
#define SDB_CPATCH_CLONES
#else
#define SDB_CPATCH_CLONES __attribute__((target_clones("avx2", "default")))
#endif

namespace sdb::cpatch {

// The c-patch's four triangular pieces: piece i has corners i, i+1 and the quad's centre
// (1/2, 1/2); its quartic Bezier points b^i_klm (k towards corner i, l towards corner i+1,
// m towards the centre) are listed in this order.
constexpr int kQuarticPoints = 15;
// clang-format off
constexpr std::array<std::array<int, 3>, kQuarticPoints> kQuarticIndex = {{
    {4, 0, 0}, {3, 1, 0}, {3, 0, 1}, {2, 2, 0}, {2, 1, 1}, {2, 0, 2}, {1, 3, 0}, {1, 2, 1},
    {1, 1, 2}, {1, 0, 3}, {0, 4, 0}, {0, 3, 1}, {0, 2, 2}, {0, 1, 3}, {0, 0, 4}}};
// clang-format on

// Equations (3) and (4): the 4 x 15 Bezier points of a c-patch record's pieces, relative to the
// patch origin p*_0 (the record's corner-0 control vertex).
using CpatchPieces = std::array<std::array<Vec3f, kQuarticPoints>, 4>;
CpatchPieces expand_cpatch(const Vec3f* record);

// Which piece holds grid sample (i, j) of an N x N grid (integer test, so ties are decided the
// same way everywhere): 0 below both diagonals, 1 right, 2 above, 3 left.
int cpatch_piece(int i, int j, int rate);

class SampleGrid {
 public:
  explicit SampleGrid(int rate);

  int rate() const { return rate_; }
  int samples() const { return rate_ * rate_; }
  // Cubic Bernstein weight B_k(u_i) at cubic_[k * N + i], derivative at cubic_du_[k * N + i].
  const float* cubic(int k) const { return &cubic_[k * rate_]; }
  const float* cubic_du(int k) const { return &cubic_du_[k * rate_]; }
  // c-patch samples in piece order: piece p covers [piece_begin(p), piece_begin(p + 1)); sorted
  // sample k is grid sample piece_order()[k]; its quartic weights are w[m * samples() + k].
  int piece_begin(int piece) const { return piece_begin_[piece]; }
  const int* piece_order() const { return piece_order_.data(); }
  const float* quartic(int m) const { return &quartic_[m * samples()]; }
  const float* quartic_du(int m) const { return &quartic_du_[m * samples()]; }
  const float* quartic_dv(int m) const { return &quartic_dv_[m * samples()]; }
  // Grid sample index of position m (0..N-1, from corner `side`) along quad side `side`.
  int side_sample(int side, int m) const;

 private:
  void build_cubic();
  void build_quartic();
  int rate_;
  std::vector<float> cubic_, cubic_du_;
  std::vector<int> piece_order_;
  int piece_begin_[5] = {};
  std::vector<float> quartic_, quartic_du_, quartic_dv_;
};

constexpr int kLanes = 8;

// Position and first derivatives of one patch at all samples, structure of arrays.
struct PatchScratch {
  std::vector<float> data;
  float* px = nullptr;
  float* py = nullptr;
  float* pz = nullptr;
  float* ux = nullptr;
  float* uy = nullptr;
  float* uz = nullptr;
  float* vx = nullptr;
  float* vy = nullptr;
  float* vz = nullptr;
  explicit PatchScratch(int samples = 0) { resize(samples); }
  void resize(int samples);
};

// The output's layout, shared by every backend: per quad its own N x N vertices (row j = v
// index; borders duplicated per quad, welded only by validation), 2 (N-1)^2 triangles
// (i,j),(i+1,j),(i+1,j+1) and (i,j),(i+1,j+1),(i,j+1), counter-clockwise in (u, v), hence outward
// for the mesh's counter-clockwise quads, and coords[k] = {quad, i/(N-1), j/(N-1)}. Sizes the
// position and normal arrays (zeros) for the evaluation to fill.
void grid_output_topology(int num_quads, int rate, Tessellation& out);

// The one routine both quads of an edge use for its samples: cubic Bezier (p0..p3, canonical
// order) with the weights of the canonical sample index, summed in a fixed order.
inline Vec3f border_point(const Vec3f& p0, const Vec3f& p1, const Vec3f& p2, const Vec3f& p3, float w0, float w1,
                          float w2, float w3) {
  return ((w0 * p0 + w1 * p1) + w2 * p2) + w3 * p3;
}

// Evaluates one quad's record into `positions` / `normals` (N * N entries each, row j = v index).
// Interior positions are p*_0 + the patch evaluated relative to p*_0 (README.md, "Float precision").
void evaluate_quad(const SampleGrid& grid, const Vec3f* record, bool is_cpatch, uint8_t forward_sides,
                   PatchScratch& scratch, Point3* positions, Point3* normals);

// kLanes ordinary (bicubic) quads at once, one per SIMD lane, gathering Figure 6's data straight
// from the vertex points (the record build_bicubic would write, without writing it): each quad's
// output is bit-identical to evaluate_quad's on that record, at a fraction of the instructions per
// sample.
struct BicubicLaneSource {
  const Vec3f* positions = nullptr;        // control points
  const VertexPoints* points = nullptr;    // Table 1 output
  const QuadCorner* corners[kLanes] = {};  // each quad's four corners (CpatchTopology::corners)
};
void evaluate_bicubic_lanes(const SampleGrid& grid, const BicubicLaneSource& source,
                            const uint8_t forward_sides[kLanes], Point3* const positions[kLanes],
                            Point3* const normals[kLanes]);

// The parts of evaluate_quad, exposed for tests.
// Relative to p*_0: bicubic in grid order, c-patch in piece order.
void evaluate_bicubic(const SampleGrid& grid, const Vec3f* record, PatchScratch& out);
void evaluate_cpatch(const SampleGrid& grid, const Vec3f* record, PatchScratch& out);
void write_border(const SampleGrid& grid, const Vec3f* record, uint8_t forward_sides, Point3* positions);

// Reference evaluation at any (u, v) in double precision by de Casteljau's algorithm, independent
// of the weight tables; for tests and for checking derivations.
struct PatchPoint {
  std::array<double, 3> position{}, du{}, dv{};
};
PatchPoint bicubic_at(const Vec3f* record, double u, double v);
PatchPoint cpatch_at(const Vec3f* record, double u, double v);

}  // namespace sdb::cpatch
