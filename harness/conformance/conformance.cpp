#include "harness/conformance/conformance.h"

#include <algorithm>
#include <cmath>

#include "datasets/manifest.h"
#include "harness/bench/measure.h"
#include "harness/core/errors.h"
#include "harness/core/registry.h"
#include "harness/gl/context.h"
#include "harness/gpu/testing.h"
#include "harness/mesh/acceptance.h"
#include "harness/mesh/facts.h"
#include "harness/reference/limit_evaluator.h"
#include "harness/results/bound_judgement.h"
#include "harness/validate/deviation.h"
#include "harness/validate/watertight.h"

namespace sdb::conformance {
namespace {

// Closed meshes of every kind a scheme meets: all-regular, valence 3 to 8, triangles, creases,
// the papers' stand-ins; the real control meshes when the corpus is there.
const std::vector<std::string> kBuiltinMeshes = {"cube",      "torus-8x8",   "quadsphere",   "pole3",       "pole8",
                                                 "icosphere", "tetrahedron", "creased-cube", "frog-standin"};
const std::vector<std::string> kCorpusMeshes = {"crane/spot_control", "crane/blub_control", "crane/spot_low_resolution"};
// One of each thing a scheme may refuse: a boundary, genus 1, quads for a triangle scheme,
// triangles for a quad scheme, creases, a non-manifold edge (below), holes.
const std::vector<std::string> kRefusableMeshes = {"open-patch", "torus-8x8", "icosphere", "cube", "creased-cube"};
const std::vector<std::string> kRefusableCorpusMeshes = {"opensubdiv/catmark_hole_test1", "opensubdiv/catmark_nonman_edges"};
constexpr const char* kFan = "three-triangle-fan";  // three triangles on one edge: not manifold

constexpr long kMaxTriangles = 150'000;  // per case: validation of larger outputs is the benchmarks'
constexpr long kRays = 20'000;           // random lines, and as many aimed at borders

ControlMesh mesh_named(const std::string& name) {
  if (name != kFan) return load_mesh(name);
  ControlMesh m;
  m.name = m.source = kFan;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  m.face_sizes = {3, 3, 3};
  m.face_vertices = {0, 1, 2, 1, 0, 3, 0, 1, 4};
  return m;
}

RunRequest request_for(const Scheme& s, Backend backend, int level) {
  return {backend, level, 0, Parameters::defaults(s.info().parameters)};
}

// The smallest default level, and the largest within the output budget.
std::vector<int> levels_for(const Scheme& s, const ControlMesh& accepted) {
  std::vector<int> levels;
  for (int level : s.info().default_levels)
    if (s.estimated_triangles(accepted, request_for(s, Backend::Cpu, level)) <= kMaxTriangles) levels.push_back(level);
  if (levels.size() > 2) levels = {levels.front(), levels.back()};
  return levels;
}

const Scheme& scheme_named(const std::string& name) {
  const Scheme* s = find_scheme(name);
  if (!s) throw std::logic_error("SDB_CONFORMANCE_SUITE names '" + name + "', which is not registered here");
  return *s;
}

std::string identifier(std::string s) {
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return s;
}

// What a scheme's declared requirements say it must refuse (an oracle beside accept_mesh).
bool must_refuse(const MeshRequirements& req, const ControlMesh& m) {
  const MeshFacts f = compute_facts(m);
  using F = MeshRequirements::Faces;
  return (req.closed && f.boundary_edges > 0) || (req.genus0 && (f.genus != 0 || f.components != 1)) ||
         (req.faces == F::TrianglesOnly && !f.all_triangles) ||
         (req.faces == F::QuadsOnly && !req.quadrangulate && !f.all_quads) ||
         (!req.creases && (f.creased_edges > 0 || f.corners > 0)) || (!req.holes && f.holes > 0) ||
         (req.manifold && !f.manifold());
}

struct Output {
  Tessellation t;
  std::shared_ptr<const ControlMesh> reference;
};

// Prepared and executed as the harness would; skips (with the reason) what the scheme declines
// or the device cannot hold.
Output run(const Scheme& s, Backend backend, const std::shared_ptr<const ControlMesh>& accepted, int level) {
  const RunRequest request = request_for(s, backend, level);
  if (auto why = declined(s, request)) throw Unsupported(*why);
  auto e = s.prepare(*accepted, request);
  execute_on(*e, backend);
  Output out{e->result(), nullptr};
  out.reference = out.t.reference ? out.t.reference : accepted;
  return out;
}

void expect_well_formed(const Tessellation& t, const LimitEvaluator& ref, bool loop) {
  ASSERT_GT(t.num_vertices(), 0u);
  ASSERT_EQ(t.normals.size(), t.positions.size());
  ASSERT_EQ(t.coords.size(), t.positions.size());
  ASSERT_EQ(t.triangles.size() % 3, 0u);
  const uint32_t n = static_cast<uint32_t>(t.num_vertices());
  EXPECT_TRUE(std::all_of(t.triangles.begin(), t.triangles.end(), [n](uint32_t i) { return i < n; }))
      << "a triangle index past the vertices";
  long outside = 0;
  for (const SurfaceCoord& c : t.coords) {
    const bool in_face = c.face < uint32_t(ref.num_ptex_faces()) && ref.has_limit(int(c.face)) && c.u >= 0 &&
                         c.u <= 1 && c.v >= 0 && c.v <= 1 && (!loop || c.u + c.v <= 1 + 1e-6f);
    outside += !in_face;
  }
  EXPECT_EQ(outside, 0) << "SurfaceCoords outside their faces (or on faces with no limit)";
}

}  // namespace

double max_distance(const std::vector<Point3>& a, const std::vector<Point3>& b) {
  double worst = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    double d2 = 0;
    for (int k = 0; k < 3; ++k) d2 += std::pow(double(a[i][k]) - b[i][k], 2);
    worst = std::max(worst, d2);
  }
  return std::sqrt(worst);
}

std::vector<std::string> conformance_meshes(const std::vector<std::string>& extra) {
  std::vector<std::string> meshes = kBuiltinMeshes;
  for (const auto& m : kCorpusMeshes)
    if (corpus_has(m)) meshes.push_back(m);
  meshes.insert(meshes.end(), extra.begin(), extra.end());
  return meshes;
}

std::vector<Case> cases_for(const std::vector<std::string>& schemes, const std::vector<std::string>& extra_meshes) {
  std::vector<Case> cases;
  for (const std::string& name : schemes) {
    const Scheme& s = scheme_named(name);
    for (const std::string& mesh : conformance_meshes(extra_meshes)) {
      ControlMesh accepted;
      try {
        accepted = accept_mesh(mesh_named(mesh), s.info());
      } catch (const InputError&) {
        continue;  // the refusal suite's
      }
      if (!compute_facts(accepted).closed) continue;
      for (Backend b : s.info().backends)
        for (int level : levels_for(s, accepted)) cases.push_back({name, b, mesh, level});
    }
  }
  return cases;
}

std::vector<Refusal> refusals_for(const std::vector<std::string>& schemes) {
  std::vector<std::string> meshes = kRefusableMeshes;
  meshes.push_back(kFan);
  for (const auto& m : kRefusableCorpusMeshes)
    if (corpus_has(m)) meshes.push_back(m);
  std::vector<Refusal> out;
  for (const std::string& name : schemes) {
    const Scheme& s = scheme_named(name);
    out.push_back({name, ""});  // the level -1 case
    for (const std::string& mesh : meshes) {
      bool refused = false;
      try {
        accept_mesh(mesh_named(mesh), s.info());
      } catch (...) {
        refused = true;
      }
      if (refused || must_refuse(s.info().accepts, mesh_named(mesh))) out.push_back({name, mesh});
    }
  }
  return out;
}

void PrintTo(const Case& c, std::ostream* out) { *out << run_name(c.scheme, c.backend, c.mesh, c.level); }

void PrintTo(const Refusal& r, std::ostream* out) { *out << r.scheme << " on " << (r.mesh.empty() ? "level -1" : r.mesh); }

std::string case_name(const ::testing::TestParamInfo<Case>& info) {
  const Case& c = info.param;
  return identifier(c.scheme + "_" + std::string(to_string(c.backend)) + "_" + c.mesh + "_" + std::to_string(c.level));
}

std::string refusal_name(const ::testing::TestParamInfo<Refusal>& info) {
  return identifier(info.param.scheme + "_" + (info.param.mesh.empty() ? "level_minus_1" : info.param.mesh));
}

void SchemeConformance::SetUp() {
  if (GetParam().backend == Backend::OpenGl) {
    if (const gl::DeviceInfo g = gl::probe(); !g.available) GTEST_SKIP() << g.reason;
  }
  vulkan_ = GetParam().backend == Backend::Vulkan;
  if (!vulkan_) return;
  if (!gpu::testing::test_context()) GTEST_SKIP() << gpu::testing::unavailable_reason();
  validation_errors_before_ = gpu::testing::begin_vulkan_test();
}

void SchemeConformance::TearDown() {
  if (vulkan_ && gpu::testing::test_context()) gpu::testing::end_vulkan_test(validation_errors_before_);
}

TEST_P(SchemeConformance, IsWatertightWithinItsBoundAndAgreesAcrossBackends) {
  const Case& c = GetParam();
  const Scheme& s = scheme_named(c.scheme);
  const SchemeInfo& info = s.info();
  const auto accepted = std::make_shared<const ControlMesh>(accept_mesh(mesh_named(c.mesh), info));
  Output out;
  try {
    out = run(s, c.backend, accepted, c.level);
  } catch (const Unsupported& e) {
    // Only the device may decline a case: every CPU backend and default level the scheme declares
    // within the cases' output budget is one it runs.
    if (!is_gpu(c.backend)) FAIL() << "declined a declared backend and level: " << e.what();
    GTEST_SKIP() << e.what();
  }
  const Tessellation& t = out.t;
  const LimitEvaluator ref(*out.reference, info.reference);
  if (info.surface_coords) {
    expect_well_formed(t, ref, info.reference == SubdivisionRule::Loop);
  } else {
    EXPECT_TRUE(t.coords.empty()) << "declares no SurfaceCoords, and has some";
    ASSERT_EQ(t.normals.size(), t.positions.size());
  }
  if (HasFatalFailure()) return;

  EXPECT_EQ(count_open_edges(t), 0) << "a closed input must give a closed surface";
  EXPECT_EQ(ray_crack_check(t, {kRays, kRays, 7}).cracks, 0);

  // The bound against the input's limit surface, where the run makes the scheme's promise (the
  // harness's rule: measure.h), and the own bound against the scheme's own control mesh.
  const bool judged = reproduces_limit(info, request_for(s, c.backend, c.level), *accepted) ||
                      info.limit == LimitClaim::Approximates;
  if (judged && bound_declared(info.bound)) {
    MeasureContext context{MachineInfo{}};
    const JudgedSurfaces surfaces{std::make_shared<const ControlMesh>(mesh_named(c.mesh)), accepted,
                                  accepted_keeps_limit(*accepted), info.reference};
    const DeviationReport d = input_limit_distance(t, surfaces, context).report;
    if (info.bound.pos_rel_diag >= 0) EXPECT_LE(d.pos_max_rel_diag, info.bound.pos_rel_diag) << "past the declared bound";
    if (info.bound.normal_deg >= 0) EXPECT_LE(d.normal_max_deg, info.bound.normal_deg) << "past the declared bound";
  }
  if (t.reference && bound_declared(info.own_bound)) {
    const DeviationReport own = measure_deviation(t, ref);
    if (info.own_bound.pos_rel_diag >= 0)
      EXPECT_LE(own.pos_max_rel_diag, info.own_bound.pos_rel_diag) << "past the declared bound on its own mesh";
    if (info.own_bound.normal_deg >= 0)
      EXPECT_LE(own.normal_max_deg, info.own_bound.normal_deg) << "past the declared bound on its own mesh";
  }

  // The backends agree where the scheme has a cpu backend to agree with (cpatch-1pass and
  // cpatch-tess are Vulkan only: their own tests compare them with cpatch-2pass on the cpu).
  const auto& backends = info.backends;
  if (c.backend == Backend::Cpu || std::find(backends.begin(), backends.end(), Backend::Cpu) == backends.end()) return;
  const Output cpu = run(s, Backend::Cpu, accepted, c.level);
  ASSERT_EQ(cpu.t.num_vertices(), t.num_vertices()) << "the backends lay the output out differently";
  EXPECT_EQ(cpu.t.triangles, t.triangles);
  if (c.backend == Backend::CpuMt) {
    EXPECT_TRUE(cpu.t.positions == t.positions) << "cpu-mt positions differ from cpu's";
    EXPECT_TRUE(cpu.t.normals == t.normals) << "cpu-mt normals differ from cpu's";
  } else {
    const double diag = bounds_of(cpu.t.positions).diagonal();
    EXPECT_LE(max_distance(cpu.t.positions, t.positions), 1e-5 * diag) << to_string(c.backend) << " positions differ from cpu's";
  }
}

TEST_P(SchemeRefusal, RefusesWithAnInputErrorNamingTheScheme) {
  const Refusal& r = GetParam();
  const Scheme& s = scheme_named(r.scheme);
  if (r.mesh.empty()) {
    const auto why = s.unsupported(request_for(s, Backend::Cpu, -1));
    ASSERT_TRUE(why.has_value()) << "level -1 must be declined with a reason";
    EXPECT_FALSE(why->empty());
    return;
  }
  const ControlMesh mesh = mesh_named(r.mesh);
  try {
    accept_mesh(mesh, s.info());
    ADD_FAILURE() << r.scheme << " declares requirements that refuse " << r.mesh << ", and accepted it";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(r.scheme), std::string::npos) << e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "refused with something other than an InputError (exit 2): " << e.what();
  }
}

}  // namespace sdb::conformance
