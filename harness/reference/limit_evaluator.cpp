#include "harness/reference/limit_evaluator.h"

#include <opensubdiv/bfr/refinerSurfaceFactory.h>
#include <opensubdiv/bfr/surface.h>
#include <opensubdiv/far/ptexIndices.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "harness/core/errors.h"
#include "harness/reference/bfr_defect.h"

namespace sdb {

namespace Bfr = OpenSubdiv::Bfr;
namespace Far = OpenSubdiv::Far;

struct LimitEvaluator::Impl {
  ControlMesh mesh;
  SubdivisionRule rule;
  std::unique_ptr<Far::TopologyRefiner> refiner;
  std::vector<int> ptex_base, ptex_sub;  // per ptex face
  std::vector<int> first_ptex;           // per base face
  std::vector<Bfr::Surface<double>> surfaces;
  std::vector<std::vector<double>> patch_points;  // xyz per patch point, per base face
  std::vector<double> local_size;                 // per base face
  std::vector<char> inexact_corner;               // per base vertex (inexact_corner_normals)
  std::vector<int> offsets;                       // per base face, into mesh.face_vertices
};

namespace {

double mean_edge_length(const ControlMesh& m, const std::vector<int>& off, int f) {
  const int n = m.face_sizes[f];
  double sum = 0;
  for (int k = 0; k < n; ++k) {
    const auto& a = m.positions[m.face_vertices[off[f] + k]];
    const auto& b = m.positions[m.face_vertices[off[f] + (k + 1) % n]];
    sum += std::sqrt(double(a[0] - b[0]) * (a[0] - b[0]) + double(a[1] - b[1]) * (a[1] - b[1]) +
                     double(a[2] - b[2]) * (a[2] - b[2]));
  }
  return sum / n;
}

// Base vertices where Bfr's normal at the vertex itself is not the limit's. Bfr's patch at such a
// corner is its irregular-patch approximation, whose corner tangents are Far's limit masks; those
// are exact only at smooth vertices of valence 3 and more, creases with the regular number of
// faces on each side (Catmull-Clark 2, Loop 3; a boundary, that many in all) and a boundary corner
// of one face. Only infinite sharpness counts: semi-sharpness is refined away by the approximation
// level. Elsewhere (darts, cone points, creases and corners of other valences) it lies up to 17
// degrees from the limit, which the refined ring converges to (schemes/fragments/README.md).
std::vector<char> inexact_corner_normals(const Far::TopologyLevel& l, SubdivisionRule rule) {
  std::vector<char> inexact(l.GetNumVertices(), 0);
  for (int v = 0; v < l.GetNumVertices(); ++v) inexact[v] = !far_tangent_masks_exact(l, v, rule, true);
  return inexact;
}

// The base vertex at the ptex corner a coord lies on, or -1: a quad's (Catmull-Clark) or a
// triangle's (Loop) corners are its vertices in order; an n-gon's sub-face k has vertex k at (0, 0).
int corner_vertex(const ControlMesh& m, const std::vector<int>& off, SubdivisionRule rule, int f, int sub, double u,
                  double v) {
  auto at = [&](int k) { return m.face_vertices[off[f] + k]; };
  if (rule == SubdivisionRule::Loop) return u == 0 && v == 0 ? at(0) : u == 1 && v == 0 ? at(1) : u == 0 && v == 1 ? at(2) : -1;
  if (m.face_sizes[f] != 4) return u == 0 && v == 0 ? at(sub) : -1;
  if (u != 0 && u != 1) return -1;
  if (v != 0 && v != 1) return -1;
  return at(v == 0 ? (u == 0 ? 0 : 1) : (u == 1 ? 2 : 3));
}

// Whether du x dv (of length `cross_len`) has a direction. Where the tangents are nearly parallel,
// or one vanishes beside the other (the fold of a flat, closed mesh or of a two-sided pillow, where
// the derivative across the fold is zero), the cross product is rounding and approximation
// residue, and its direction, up to 180 degrees off, judges nothing: below 1e-6 of the longer
// tangent's square neither normal is compared. Relative, so the same at every scale.
bool tangents_span_a_plane(double cross_len, const double du[3], const double dv[3]) {
  const double lu2 = du[0] * du[0] + du[1] * du[1] + du[2] * du[2];
  const double lv2 = dv[0] * dv[0] + dv[1] * dv[1] + dv[2] * dv[2];
  return cross_len > 1e-6 * std::max(lu2, lv2);
}

}  // namespace

LimitEvaluator::LimitEvaluator(const ControlMesh& mesh, SubdivisionRule rule, LimitAccuracy accuracy)
    : impl_(std::make_unique<Impl>()) {
  Impl& d = *impl_;
  d.mesh = mesh;
  d.rule = rule;
  d.refiner = make_refiner(mesh, rule);
  if (auto defect = bfr_overlapping_patch_defect(mesh)) throw Unsupported(*defect);
  const Far::PtexIndices ptex(*d.refiner);
  d.inexact_corner = inexact_corner_normals(d.refiner->GetLevel(0), rule);
  const int nf = num_faces(mesh);
  const int regular = rule == SubdivisionRule::Loop ? 3 : 4;
  d.first_ptex.resize(nf);
  for (int f = 0; f < nf; ++f) {
    d.first_ptex[f] = ptex.GetFaceId(f);
    const int subfaces = mesh.face_sizes[f] == regular ? 1 : mesh.face_sizes[f];
    if (rule == SubdivisionRule::Loop && mesh.face_sizes[f] != 3)
      throw InputError(face_location(mesh, f), "Loop subdivision needs triangles, face has " +
                                                   std::to_string(mesh.face_sizes[f]) + " vertices");
    for (int k = 0; k < subfaces; ++k) {
      d.ptex_base.push_back(f);
      d.ptex_sub.push_back(k);
    }
  }
  Bfr::RefinerSurfaceFactory<>::Options options;
  options.SetApproxLevelSmooth(accuracy.smooth);
  options.SetApproxLevelSharp(accuracy.sharp);
  const Bfr::RefinerSurfaceFactory<> factory(*d.refiner, options);

  std::vector<double> points(3 * mesh.positions.size());
  for (size_t v = 0; v < mesh.positions.size(); ++v)
    for (int k = 0; k < 3; ++k) points[3 * v + k] = mesh.positions[v][k];
  const auto off = face_offsets(mesh);
  d.offsets = off;
  d.surfaces.resize(nf);
  d.patch_points.resize(nf);
  d.local_size.resize(nf);
  for (int f = 0; f < nf; ++f) {
    d.local_size[f] = mean_edge_length(mesh, off, f);
    if (!factory.InitVertexSurface(f, &d.surfaces[f])) continue;  // hole or no limit surface
    d.patch_points[f].resize(3 * d.surfaces[f].GetNumPatchPoints());
    d.surfaces[f].PreparePatchPoints(points.data(), 3, d.patch_points[f].data(), 3);
  }
}

LimitEvaluator::~LimitEvaluator() = default;

int LimitEvaluator::num_ptex_faces() const { return static_cast<int>(impl_->ptex_base.size()); }

std::pair<int, int> LimitEvaluator::base_face(int ptex_face) const {
  return {impl_->ptex_base.at(ptex_face), impl_->ptex_sub.at(ptex_face)};
}

int LimitEvaluator::first_ptex_face(int base_face) const { return impl_->first_ptex.at(base_face); }

bool LimitEvaluator::has_limit(int ptex_face) const {
  return impl_->surfaces.at(impl_->ptex_base.at(ptex_face)).IsValid();
}

LimitSample LimitEvaluator::evaluate(SurfaceCoord c) const {
  const Impl& d = *impl_;
  if (c.face >= d.ptex_base.size()) throw std::out_of_range("LimitEvaluator: ptex face out of range");
  const int f = d.ptex_base[c.face];
  const Bfr::Surface<double>& s = d.surfaces[f];
  if (!s.IsValid()) throw std::invalid_argument("LimitEvaluator: face " + std::to_string(f) + " has no limit surface");
  double uv[2] = {c.u, c.v};
  const Bfr::Parameterization param = s.GetParameterization();
  double scale = 1.0;  // d(face coord) / d(ptex coord)
  if (param.HasSubFaces()) {
    // Normalized sub-face coordinates are Ptex coordinates (Bfr::Parameterization docs); a
    // sub-face spans half a unit of the face's tiled (u,v), hence the derivative scale.
    const double sub[2] = {c.u, c.v};
    param.ConvertNormalizedSubFaceToCoord(d.ptex_sub[c.face], sub, uv);
    scale = 0.5;
  }
  LimitSample out;
  double p[3], du[3], dv[3];
  s.Evaluate(uv, d.patch_points[f].data(), 3, p, du, dv);
  double n[3] = {du[1] * dv[2] - du[2] * dv[1], du[2] * dv[0] - du[0] * dv[2], du[0] * dv[1] - du[1] * dv[0]};
  double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (!tangents_span_a_plane(len, du, dv)) len = 0;  // no normal to judge by: a fold, a face of no area
  const int corner = corner_vertex(d.mesh, d.offsets, d.rule, f, d.ptex_sub[c.face], c.u, c.v);
  if (corner >= 0 && d.inexact_corner[corner]) len = 0;  // no normal to judge by (see above)
  for (int k = 0; k < 3; ++k) {
    out.position[k] = p[k];
    out.du[k] = du[k] * scale;
    out.dv[k] = dv[k] * scale;
    out.normal[k] = len > 0 ? n[k] / len : 0.0;
  }
  return out;
}

double LimitEvaluator::local_size(int ptex_face) const { return impl_->local_size.at(impl_->ptex_base.at(ptex_face)); }

const ControlMesh& LimitEvaluator::mesh() const { return impl_->mesh; }

SubdivisionRule LimitEvaluator::rule() const { return impl_->rule; }

}  // namespace sdb
