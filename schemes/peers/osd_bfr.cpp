#include <opensubdiv/bfr/refinerSurfaceFactory.h>
#include <opensubdiv/bfr/surface.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "harness/core/errors.h"
#include "harness/reference/bfr_defect.h"
#include "harness/reference/shared_layout.h"
#include "harness/reference/surface_normal.h"
#include "schemes/peers/limit_stencils.h"
#include "schemes/peers/peers.h"

namespace sdb {
namespace {

namespace Bfr = OpenSubdiv::Bfr;
namespace Far = OpenSubdiv::Far;

// Bfr's default approximation (level 2) misses the limit near extraordinary vertices by
// 2e-3..8e-3 of the diagonal at 1/32 of a face (measured); raise it to what the rate samples:
// level L is exact at ptex distance >= 2^-(L-1) from the corner, so L = log2(segments) + 2.
int rate_level(int rate) { return std::min(10, 2 + static_cast<int>(std::ceil(std::log2(std::max(1, rate - 1))))); }

// Bfr's deepest approximation level for a mesh and rate (below).
int approximation_level(const ControlMesh& mesh, int rate) { return has_sharp_features(mesh) ? 10 : rate_level(rate); }

// Far's adaptive refinement, which Bfr's irregular patches come from, isolates an interior vertex
// with an infinitely sharp edge (a dart, or a crease of irregular valence) only to the smooth
// level, whatever the sharp level says (Far's FeatureMask::ReduceFeatures, with inf-sharp patches,
// drops them past the secondary level), and the patch it ends a dart with misses the limit at the
// dart's own corner: 4.8e-5 of the diagonal at level 4 (rate 5) and 1.6e-5 at 5 (rate 9) on
// loop_cubes_infsharp, 1.2e-4 and 5.9e-5 on loop_icos_infsharp. A face with such a corner gets
// level 10 as smooth level too (then 5.3e-8 and 1.5e-6).
bool corner_isolated_at_smooth_level(const Far::TopologyLevel& l, int f) {
  for (int v : l.GetFaceVertices(f)) {
    if (l.IsVertexBoundary(v)) continue;
    for (int e : l.GetVertexEdges(v))
      if (l.IsEdgeInfSharp(e)) return true;
  }
  return false;
}

// At an infinitely sharp corner (a vertex of infinite sharpness, or where three infinitely sharp
// edges meet) Bfr ends its deepest level with patches whose normal at the vertex is that level's
// face's, and the faces' normals reach the limit's only as about 0.8 to 0.85 a level (Far's
// refinement, measured: 45 degrees at level 0, 5.63 at 10, 3.61 at 12 on the cone point of
// loop_cubes_infsharp; 7.02 at 10 where three creases meet on catmark_inf_crease1): so Bfr's normal
// at level 10, the deepest it takes, is not the limit's: the peer gives no normal there. Where
// the face is a sector of its own (both its edges at the vertex infinitely sharp: a corner patch)
// Bfr's is the limit's (within the bound on every corpus shape). Corner k of face f.
bool normal_is_deepest_face(const Far::TopologyLevel& l, int f, int k) {
  const int v = l.GetFaceVertices(f)[k];
  if (l.GetVertexRule(v) != OpenSubdiv::Sdc::Crease::RULE_CORNER) return false;
  int inf_edges = 0;
  for (int e : l.GetVertexEdges(v)) inf_edges += l.IsEdgeInfSharp(e) || l.IsEdgeBoundary(e);
  if (!l.IsVertexInfSharp(v) && inf_edges < 3) return false;  // a semi-sharp corner: decayed at level 10
  const Far::ConstIndexArray fe = l.GetFaceEdges(f);
  const int before = fe[(k + fe.size() - 1) % fe.size()], after = fe[k];
  const auto sharp = [&](int e) { return l.IsEdgeInfSharp(e) || l.IsEdgeBoundary(e); };
  return !(sharp(before) && sharp(after));
}

// Real: float, or double where the approximation level is deep (below).
template <class Real>
class OsdBfrEvaluation final : public Evaluation {
 public:
  OsdBfrEvaluation(const ControlMesh& mesh, SubdivisionRule rule, int rate, Backend backend)
      : control_(mesh), refiner_(make_refiner(mesh, rule)), backend_(backend) {
    points_.resize(3 * mesh.positions.size());
    for (size_t v = 0; v < mesh.positions.size(); ++v)
      for (int k = 0; k < 3; ++k) points_[3 * v + k] = mesh.positions[v][k];
    SharedLayout layout = make_shared_layout(*refiner_, rule, rate - 1);
    out_ = std::move(layout.topology);
    owned_ = std::move(layout.owned_by_face);
    Bfr::RefinerSurfaceFactory<>::Options options, deepest;
    const int level = rate_level(rate);
    // Next to creases, corners and boundaries Bfr's irregular patches converge only as 2^-L with
    // the level (measured: 3.8e-4 of the diagonal at L = 4 on catmark_cubes_infsharp, 1.3e-5 at
    // 8, 9e-8 at 10; Loop's semi-sharp cube needs the sharp level 8): such meshes' sharp faces
    // get 10. Their smooth irregular faces keep the rate's level: at level 10 a valence-3 vertex's
    // corner tangent is 2^10 times a difference of float patch points whose stencils carry float
    // error, and its normal turned by up to 7 degrees with a one-ulp change of the input
    // (pmp/suzanne, placed at unit size: failed, its copy scaled by 1e-6 passed).
    const bool sharp = has_sharp_features(mesh);
    options.SetApproxLevelSmooth(level).SetApproxLevelSharp(sharp ? 10 : std::max(level, 6));
    deepest.SetApproxLevelSmooth(10).SetApproxLevelSharp(10);
    const Bfr::RefinerSurfaceFactory<> factory(*refiner_, options), deepest_factory(*refiner_, deepest);
    const int nf = num_faces(mesh);
    surfaces_.resize(nf);
    patch_points_.resize(nf);
    for (int f = 0; f < nf; ++f) {
      const bool deep = corner_isolated_at_smooth_level(refiner_->GetLevel(0), f);
      if (owned_[f].empty() || !(deep ? deepest_factory : factory).InitVertexSurface(f, &surfaces_[f])) continue;
      patch_points_[f].resize(3 * surfaces_[f].GetNumPatchPoints());
    }
    out_.positions.resize(out_.coords.size());
    out_.normals.resize(out_.coords.size());
    offsets_ = face_offsets(mesh);
    origins_.resize(nf);
    corner_without_normal_.assign(mesh.face_vertices.size(), 0);
    for (int f = 0; f < nf; ++f)
      for (int k = 0; k < mesh.face_sizes[f]; ++k)
        corner_without_normal_[offsets_[f] + k] = normal_is_deepest_face(refiner_->GetLevel(0), f, k);
    for (int f = 0; f < nf; ++f)
      if (surfaces_[f].IsValid() && !surfaces_[f].IsRegular())
        for (const auto& o : owned_[f]) {
          const int corner = corner_of(surfaces_[f].GetParameterization(), o.u, o.v);
          sharp_corners_ += corner >= 0 && corner_without_normal_[offsets_[f] + corner];
        }
  }

  void execute() override {
    if (backend_ == Backend::CpuMt) {
      tbb::parallel_for(tbb::blocked_range<int>(0, static_cast<int>(surfaces_.size()), 16),
                        [&](const tbb::blocked_range<int>& r) {
                          for (int f = r.begin(); f < r.end(); ++f) evaluate_face(f);
                        });
    } else {
      for (int f = 0; f < static_cast<int>(surfaces_.size()); ++f) evaluate_face(f);
    }
  }

  const Tessellation& result() override { return out_; }
  size_t bytes_out() const override { return out_.positions.size() * 2 * sizeof(Point3); }
  std::vector<std::string> notes() const override {
    if (sharp_corners_ == 0) return {};
    return {"no normal at " + std::to_string(sharp_corners_) +
            " infinitely sharp corners, where Bfr's is its deepest level's face's, not the limit's"};
  }

 private:
  // The patch points relative to a control point near the samples: at approximation level 10
  // the corner patches of an irregular face are 2^-10 of it, and their points in the mesh's own
  // coordinates (float) left tangents of rounding noise there (catmark_pawn 170 degrees, the
  // valence-64 pole 18.6, at positions right to 1e-6). Relative to the face's first control
  // point for most samples; a sample at an irregular face's corner, where the deepest patch is,
  // relative to that corner's vertex (loop_xord_interior: 41.6 degrees from the first).
  void evaluate_face(int f) {
    const Bfr::Surface<Real>& s = surfaces_[f];
    if (!s.IsValid()) return;
    const Bfr::Parameterization param = s.GetParameterization();
    prepare_relative(f, control_.positions[control_.face_vertices[offsets_[f]]]);
    std::vector<std::pair<SharedLayout::Owned, int>> corners;  // (sample, corner)
    for (const auto& o : owned_[f]) {
      const int corner = s.IsRegular() ? -1 : corner_of(param, o.u, o.v);
      if (corner >= 0) corners.push_back({o, corner});
      else evaluate(s, f, o);
    }
    for (const auto& [o, corner] : corners) {
      // Relative to the limit point itself (an extraordinary vertex's limit can lie far from its
      // control point: 0.3 of a 2.4 wide mesh on loop_xord_interior), found relative to the corner.
      prepare_relative(f, control_.positions[control_.face_vertices[offsets_[f] + corner]]);
      evaluate(s, f, o);
      prepare_relative(f, out_.positions[o.vertex]);
      evaluate(s, f, o);
      if (corner_without_normal_[offsets_[f] + corner]) out_.normals[o.vertex] = {0, 0, 0};
    }
  }

  // Patch points of face f relative to `origin` (kept in origins_[f]).
  void prepare_relative(int f, const Point3& origin) {
    const Bfr::Surface<Real>& s = surfaces_[f];
    Real* patch = patch_points_[f].data();
    s.GatherControlPoints(points_.data(), 3, patch, 3);
    for (int i = 0; i < s.GetNumControlPoints(); ++i)
      for (int k = 0; k < 3; ++k) patch[3 * i + k] -= origin[k];
    s.ComputePatchPoints(patch, 3);
    origins_[f] = origin;
  }

  static int corner_of(const Bfr::Parameterization& param, float u, float v) {
    for (int k = 0; k < param.GetFaceSize(); ++k) {
      float c[2];
      param.GetVertexCoord(k, c);
      if (c[0] == u && c[1] == v) return k;
    }
    return -1;
  }

  void evaluate(const Bfr::Surface<Real>& s, int f, const SharedLayout::Owned& o) {
    const Real* patch = patch_points_[f].data();
    const Point3& origin = origins_[f];
    const Real uv[2] = {o.u, o.v};
    Real p[3], du[3], dv[3];
    s.Evaluate(uv, patch, 3, p, du, dv);
    out_.positions[o.vertex] = {float(p[0] + origin[0]), float(p[1] + origin[1]), float(p[2] + origin[2])};
    // Where a derivative vanishes (a face folded onto an edge of valence 2) or the two are parallel
    // (a boundary vertex of one face under edge-only interpolation, where du = -dv) du x dv has no
    // direction, and Bfr's patches next to it are no guide to the one-sided limit either (its
    // normal 1e-3 of the way inside was 6.6 degrees off on catmark_gregory_test5, where the face
    // is flat): the peer gives no normal there (45 degrees off on loop_saddle_edgeonly before).
    if (tangents_degenerate(du, dv)) {
      out_.normals[o.vertex] = {0, 0, 0};
      return;
    }
    const float a[3] = {float(du[0]), float(du[1]), float(du[2])}, b[3] = {float(dv[0]), float(dv[1]), float(dv[2])};
    out_.normals[o.vertex] = unit_cross(a, b);
  }

  const ControlMesh control_;
  std::unique_ptr<Far::TopologyRefiner> refiner_;
  Backend backend_;
  std::vector<std::vector<SharedLayout::Owned>> owned_;
  std::vector<Real> points_;  // the control points, xyz
  std::vector<Bfr::Surface<Real>> surfaces_;
  std::vector<std::vector<Real>> patch_points_;
  std::vector<int> offsets_;     // per face, into control_.face_vertices
  std::vector<char> corner_without_normal_;  // per face corner (control_.face_vertices)
  long sharp_corners_ = 0;                   // output vertices at such corners
  std::vector<Point3> origins_;  // per face: what its patch points are relative to
  Tessellation out_;
};

// Where OpenSubdiv 3.5.0's Bfr is not the limit, measured against Far's refinement (the
// yardstick's local refinement, harness/reference): next to non-manifold vertices and edges (up
// to 2% of the diagonal, catmark_nonman_edges) and next to Chaikin creases still semi-sharp
// (5.2e-4 and 5.9 degrees, catmark_chaikin1). The peer refuses those meshes up front.
std::optional<std::string> bfr_not_the_limit(const ControlMesh& mesh, SubdivisionRule rule) {
  if (mesh.crease_method == CreaseMethod::Chaikin) {
    for (const EdgeCrease& c : mesh.creases)
      if (c.sharpness > 0 && c.sharpness < 10)
        return mesh.source + ": Chaikin creases of finite sharpness, where OpenSubdiv 3.5.0's Bfr is not the limit (5e-4 "
                             "of the diagonal and 6 degrees off next to the corners they meet)";
  }
  const auto refiner = make_refiner(mesh, rule);
  const Far::TopologyLevel& l = refiner->GetLevel(0);
  // A vertex no face uses is no feature of the surface (Far calls it non-manifold).
  for (int v = 0; v < l.GetNumVertices(); ++v)
    if (l.IsVertexNonManifold(v) && l.GetVertexFaces(v).size() > 0)
      return mesh.source + ": non-manifold at vertex " + std::to_string(v) +
             ", where OpenSubdiv 3.5.0's Bfr is not the limit (up to 2% of the diagonal off Far's refinement)";
  return std::nullopt;
}

class OsdBfr final : public Scheme {
 public:
  explicit OsdBfr(SubdivisionRule rule) : rule_(rule) {
    const bool loop = rule == SubdivisionRule::Loop;
    info_.name = loop ? "osd-bfr-loop" : "osd-bfr";
    info_.paper = "peer: OpenSubdiv 3.5 Bfr surfaces, uniform tessellation";
    info_.description = std::string(loop ? "Loop" : "Catmull-Clark") +
                        " Bfr::Tessellation at rate N per face, shared borders, positions and normals";
    info_.role = SchemeRole::Peer;
    // Float evaluation at a raised approximation level: 1.0e-6 of the diagonal at worst in the
    // default set (fandisk), normals 1.9 degrees (the sword) next to extraordinary vertices.
    info_.bound = {1e-5, 5};
    info_.reference = rule;
    // The anchors: no peer of their own (the gate reads them against the write-bandwidth probe).
    if (!loop) info_.default_meshes = {"torus", "quadsphere", "pole3", "pole8", "icosphere", "creased-cube"};
    info_.level_kind = LevelKind::Rate;
    info_.backends = {Backend::Cpu, Backend::CpuMt};
    info_.default_levels = {2, 5, 9, 17, 33};
    info_.accepts.faces = loop ? MeshRequirements::Faces::TrianglesOnly : MeshRequirements::Faces::Any;
    info_.accepts.manifold = false;
    info_.accepts.creases = true;
    info_.accepts.holes = true;
  }
  const SchemeInfo& info() const override { return info_; }
  std::optional<std::string> unsupported(const RunRequest& r) const override {
    if (r.level < 2 || r.level > 129) return "rate N must be 2..129";
    return std::nullopt;
  }
  std::unique_ptr<Evaluation> prepare(const ControlMesh& mesh, const RunRequest& r) const override {
    if (auto defect = bfr_overlapping_patch_defect(mesh)) throw Unsupported(*defect);
    if (auto off = bfr_not_the_limit(mesh, rule_)) throw Unsupported(*off);
    // Deep irregular patches (level 8 and more: sharp meshes, rates past 33) are 2^-8 of a face and
    // less; float leaves their tangents to rounding noise even relative to the point evaluated
    // (loop_xord_interior's extraordinary corner: 12.5 degrees), double does not.
    if (approximation_level(mesh, r.level) >= 8)
      return std::make_unique<OsdBfrEvaluation<double>>(mesh, rule_, r.level, r.backend);
    return std::make_unique<OsdBfrEvaluation<float>>(mesh, rule_, r.level, r.backend);
  }

 private:
  SubdivisionRule rule_;
  SchemeInfo info_;
};

}  // namespace

std::unique_ptr<Scheme> make_osd_bfr(SubdivisionRule rule) { return std::make_unique<OsdBfr>(rule); }

}  // namespace sdb
