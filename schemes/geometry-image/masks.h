// MaskPass: the masks of Table 1 as image-to-image passes, one pass per mask as the paper's
// fragment programs (and this scheme's future GLSL compute shaders) apply them.
//
// Data layout (mirrored by the GPU passes). A padded image of side S = n + 2 holds an n x n
// geometry image with its one-sample border (Section 3). It is one flat float array of three
// planes, x then y then z, each S * S floats in row-major order:
//     value(c, col, row) = data[(c * S + row) * S + col],   col, row in [0, S)
// Padded (col, row) is image (col - 1, row - 1). Pass sizes, for a source of side S:
//     split L:          S -> 2S - 1   (bilinear quadrisection of the whole padded image)
//     average A + crop: M -> M - 2    (the averaging mask, dropping the outer ring it cannot reach)
//     fused L + A:      S -> 2S - 3   (the bicubic subdivision masks; equals A[L[.]] up to rounding)
//     limit E, normal:  S -> (S - 2)^2 positions / normals (Point3, row-major, vertex y * n + x),
//                       as two passes or one fused pass with identical results
// so level k of an n0 x n0 image has n_k = (n0 - 1) 2^k + 1 samples a side and S_k = n_k + 2.
// The border of g^{k+1} comes out of the masks applied to g^k's border; it is never re-padded.
//
// Bit-identical fused samples, by construction. The cut identifies samples by 180-degree turns
// of the image plane (image.h). Every mask here is point-symmetric (E, A, L) or point-
// antisymmetric (T_s, T_t), and every pass adds the samples of opposite stencil positions first,
// (W + E), (N + S), (NW + SE), (NE + SW), then adds those pair sums in a fixed order. A turn only
// swaps the two members of each pair, and IEEE addition is commutative, so identified samples
// get bit-identical values (the tangents get exactly negated values, and their cross product the
// same normal); by induction over passes every level keeps the cut symmetry bit for bit, border
// included. The normal pass adds +0 to its results, because a zero tangent component is +0 on
// both sides (x - x) and its products may differ in the sign of zero. A GPU port must keep this
// order and forbid reassociation and contraction into fma (GLSL `precise`).
#pragma once

#include <array>
#include <vector>

#include "harness/core/control_mesh.h"
#include "schemes/geometry-image/image.h"

namespace sdb::gim {

struct PaddedImage {
  int side = 0;
  std::vector<float> data;  // 3 * side * side

  PaddedImage() = default;
  explicit PaddedImage(int s) : side(s), data(3 * static_cast<size_t>(s) * s, 0.0f) {}
  float* plane(int c) { return data.data() + static_cast<size_t>(c) * side * side; }
  const float* plane(int c) const { return data.data() + static_cast<size_t>(c) * side * side; }
  Point3 at(int col, int row) const {
    const size_t i = static_cast<size_t>(row) * side + col;
    return {plane(0)[i], plane(1)[i], plane(2)[i]};
  }
};

// Half-open range of destination rows a call computes; passes are split by rows across threads.
struct RowRange {
  int begin = 0, end = 0;
};

// Padding: for every padded position, the closed-mesh vertex it holds (CutSymmetry::vertex).
std::vector<int> padding_gather_table(const CutSymmetry& sym);
// g0 from the control mesh's positions through the gather table: dst(col, row) = vertex positions.
void pad_pass(const std::vector<int>& gather, const Point3* control, PaddedImage& dst, RowRange rows);

// Splitting L (Table 1): even-even copies, odd-even / even-odd average 2, odd-odd average 4.
void split_pass(const PaddedImage& src, PaddedImage& dst, RowRange rows);
// Averaging A (1/16 [1 2 1; 2 4 2; 1 2 1]) of an L image, cropped by one sample on every side.
void average_pass(const PaddedImage& src, PaddedImage& dst, RowRange rows);
// L and A in one pass: the bicubic B-spline subdivision masks (1/64 [1 6 1]^T[1 6 1] at vertices,
// 1/16 [1 6 1]^T[1 1] at edges, 1/4 [1 1]^T[1 1] at faces), cropped like average_pass.
void split_average_pass(const PaddedImage& src, PaddedImage& dst, RowRange rows);

// Limit E (1/36 [1 4 1; 4 16 4; 1 4 1]) at every unpadded sample; rows are image rows.
void limit_pass(const PaddedImage& src, Point3* positions, RowRange rows);
// Tangents T_s (1/6 [-1 0 1; -4 0 4; -1 0 1], s along columns) and T_t (its transpose) and
// n = unit(T_s x T_t); the scale 1/6 is left out since only the direction is kept.
void normal_pass(const PaddedImage& src, Point3* normals, RowRange rows);
// E and the normals in one pass, reading g^k once (bit-identical to limit_pass + normal_pass).
void limit_normal_pass(const PaddedImage& src, Point3* positions, Point3* normals, RowRange rows);

// At the cut vertices a, b, c, d both tangent masks give exactly zero for any image (equation 1
// is point-symmetric about them), so the normal pass leaves them undefined. With equation (2)
// holding, the limit tangent plane there is spanned by the subdominant left eigenvectors of the
// appendix's perturbed subdivision matrix: T1 = g(c+u) - g(c+e) and T2 = g(c+u+e) - g(c-u+e),
// e the inward and u the along-border step (CutSymmetry::inward / along), n = unit(T2 x T1).
// One invocation per cut vertex, with stencils computed once per level size.
struct CutVertexStencil {
  int output = 0;                      // vertex index in the unpadded n x n output
  int centre = 0, u = 0, e = 0, ue = 0, mu_e = 0;  // padded-plane offsets of c, c+u, c+e, c+u+e, c-u+e
};
std::array<CutVertexStencil, 4> cut_vertex_stencils(int n);
void cut_vertex_normal_pass(const PaddedImage& src, const std::array<CutVertexStencil, 4>& stencils, Point3* normals);

}  // namespace sdb::gim
