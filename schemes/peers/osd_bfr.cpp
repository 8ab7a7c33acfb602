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

class OsdBfrEvaluation final : public Evaluation {
 public:
  OsdBfrEvaluation(const ControlMesh& mesh, SubdivisionRule rule, int rate, Backend backend)
      : control_(mesh), refiner_(make_refiner(mesh, rule)), backend_(backend) {
    SharedLayout layout = make_shared_layout(*refiner_, rule, rate - 1);
    out_ = std::move(layout.topology);
    owned_ = std::move(layout.owned_by_face);
    // Bfr's default approximation (level 2) misses the limit near extraordinary vertices by
    // 2e-3..8e-3 of the diagonal at 1/32 of a face (measured); raise it to what the rate samples:
    // level L is exact at ptex distance >= 2^-(L-1) from the corner, so L = log2(segments) + 2.
    Bfr::RefinerSurfaceFactory<>::Options options;
    const int level = std::min(10, 2 + static_cast<int>(std::ceil(std::log2(std::max(1, rate - 1)))));
    // Next to creases, corners and boundaries Bfr's irregular patches converge only as 2^-L with
    // the level (measured: 3.8e-4 of the diagonal at L = 4 on catmark_cubes_infsharp, 1.3e-5 at
    // 8, 9e-8 at 10; Loop's semi-sharp cube needs the sharp level 8): such meshes' sharp faces
    // get 10. Their smooth irregular faces keep the rate's level: at level 10 a valence-3 vertex's
    // corner tangent is 2^10 times a difference of float patch points whose stencils carry float
    // error, and its normal turned by up to 7 degrees with a one-ulp change of the input
    // (pmp/suzanne, placed at unit size: failed, its copy scaled by 1e-6 passed).
    const bool sharp = has_sharp_features(mesh);
    options.SetApproxLevelSmooth(level).SetApproxLevelSharp(sharp ? 10 : std::max(level, 6));
    const Bfr::RefinerSurfaceFactory<> factory(*refiner_, options);
    const int nf = num_faces(mesh);
    surfaces_.resize(nf);
    patch_points_.resize(nf);
    for (int f = 0; f < nf; ++f) {
      if (owned_[f].empty() || !factory.InitVertexSurface(f, &surfaces_[f])) continue;
      patch_points_[f].resize(3 * surfaces_[f].GetNumPatchPoints());
    }
    out_.positions.resize(out_.coords.size());
    out_.normals.resize(out_.coords.size());
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

 private:
  void evaluate_face(int f) {
    const Bfr::Surface<float>& s = surfaces_[f];
    if (!s.IsValid()) return;
    float* patch = patch_points_[f].data();
    s.PreparePatchPoints(control_.positions[0].data(), 3, patch, 3);
    for (const auto& o : owned_[f]) {
      const float uv[2] = {o.u, o.v};
      float p[3], du[3], dv[3];
      s.Evaluate(uv, patch, 3, p, du, dv);
      out_.positions[o.vertex] = {p[0], p[1], p[2]};
      out_.normals[o.vertex] = unit_cross(du, dv);
    }
  }

  const ControlMesh control_;
  std::unique_ptr<Far::TopologyRefiner> refiner_;
  Backend backend_;
  std::vector<std::vector<SharedLayout::Owned>> owned_;
  std::vector<Bfr::Surface<float>> surfaces_;
  std::vector<std::vector<float>> patch_points_;
  Tessellation out_;
};

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
    return std::make_unique<OsdBfrEvaluation>(mesh, rule_, r.level, r.backend);
  }

 private:
  SubdivisionRule rule_;
  SchemeInfo info_;
};

}  // namespace

std::unique_ptr<Scheme> make_osd_bfr(SubdivisionRule rule) { return std::make_unique<OsdBfr>(rule); }

}  // namespace sdb
