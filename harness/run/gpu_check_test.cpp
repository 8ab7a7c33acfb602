// The GPU check's plan (schemes from the registry, their meshes and two output sizes, the CPU row
// beside each) and its one-screen summary; nothing is measured.
#include <gtest/gtest.h>

#include <algorithm>

#include "harness/run/gpu_check_plan.h"
#include "harness/run/gpu_check_summary.h"
#include "harness/core/registry.h"

namespace sdb {
namespace {

// Schemes registered by this test alone: a GPU peer with its own cpu-mt path (as issue 43's
// halfedge peers will be), a Vulkan-only method read against a CPU peer, that peer, and a test
// scheme with a Vulkan path, which the check must leave out. Nothing prepares them.
class FakeScheme final : public Scheme {
 public:
  explicit FakeScheme(SchemeInfo info) : info_(std::move(info)) {}
  const SchemeInfo& info() const override { return info_; }
  std::optional<std::string> unsupported(const RunRequest& r) const override {
    if (r.level < 1 || r.level > max_level_) return "depth must be 1.." + std::to_string(max_level_);
    return std::nullopt;
  }
  std::unique_ptr<Evaluation> prepare(const ControlMesh&, const RunRequest&) const override { return nullptr; }
  int max_level_ = 8;

 private:
  SchemeInfo info_;
};

SchemeInfo fake_info(const char* name, SchemeRole role, std::vector<Backend> backends) {
  SchemeInfo i;
  i.name = name;
  i.role = role;
  i.level_kind = LevelKind::Depth;
  i.backends = std::move(backends);
  i.default_levels = {1, 2};
  i.accepts.faces = MeshRequirements::Faces::QuadsOnly;
  return i;
}

std::vector<std::unique_ptr<Scheme>> fake_schemes() {
  std::vector<std::unique_ptr<Scheme>> s;
  SchemeInfo gpu_peer = fake_info("fake-gpu-peer", SchemeRole::Peer, {Backend::Cpu, Backend::CpuMt, Backend::Vulkan});
  gpu_peer.default_meshes = {"quadsphere", "torus-40x50"};
  gpu_peer.headline_runs = {{"torus-40x50", Backend::Cpu, 4}};
  s.push_back(std::make_unique<FakeScheme>(gpu_peer));
  SchemeInfo cpu_peer = fake_info("fake-cpu-peer", SchemeRole::Peer, {Backend::Cpu, Backend::CpuMt});
  s.push_back(std::make_unique<FakeScheme>(cpu_peer));
  SchemeInfo method = fake_info("fake-vulkan-method", SchemeRole::Method, {Backend::Vulkan});
  method.peer = "fake-cpu-peer";
  method.large_meshes = {"no-such-mesh", "torus-40x50"};
  auto m = std::make_unique<FakeScheme>(method);
  m->max_level_ = 4;  // a device limit: its outputs stop at 1.02 M triangles
  s.push_back(std::move(m));
  s.push_back(std::make_unique<FakeScheme>(fake_info("fake-test-scheme", SchemeRole::Test, {Backend::Vulkan})));
  return s;
}
SDB_REGISTER_SCHEMES(gpu_check_test, fake_schemes);

const CheckGroup* group(const CheckPlan& plan, const std::string& scheme, int size) {
  for (const CheckGroup& g : plan.groups)
    if (g.scheme == scheme && g.size == size) return &g;
  return nullptr;
}

TEST(GpuCheckPlan, EveryRegisteredGpuSchemeJoinsAtTwoSizesBesideACpuRow) {
  MeasureContext context(MachineInfo{});
  const CheckPlan plan = plan_gpu_check(kGpuCheckBounds, false, {Backend::Vulkan}, context);
  // torus-40x50: 2,000 quads, 2 x 2000 x 4^k triangles: depth 6 = 16.4 M, the one within
  // 10-60 M; depth 7 (65.5 M) is past 60 M, so the second size is depth 5 (4.1 M).
  const CheckGroup* peer1 = group(plan, "fake-gpu-peer", 1);
  const CheckGroup* peer2 = group(plan, "fake-gpu-peer", 2);
  ASSERT_TRUE(peer1 && peer2);
  EXPECT_EQ(peer1->mesh, "torus-40x50");  // its headline mesh before its default meshes
  EXPECT_EQ(peer1->level, 6);
  EXPECT_EQ(peer1->triangles, 16'384'000);
  EXPECT_EQ(peer2->level, 5);
  ASSERT_EQ(peer1->runs.size(), 2u);
  EXPECT_EQ(peer1->runs[0].name(), "fake-gpu-peer/vulkan/torus-40x50/6");
  EXPECT_EQ(peer1->runs[1].name(), "fake-gpu-peer/cpu-mt/torus-40x50/6");  // its own CPU path
  // The Vulkan-only method: its large mesh that exists, its largest level (none reaches 10 M),
  // beside its peer's cpu-mt row at the same depth.
  const CheckGroup* method1 = group(plan, "fake-vulkan-method", 1);
  ASSERT_TRUE(method1);
  EXPECT_EQ(method1->mesh, "torus-40x50");
  EXPECT_EQ(method1->level, 4);
  ASSERT_EQ(method1->runs.size(), 2u);
  EXPECT_EQ(method1->runs[1].name(), "fake-cpu-peer/cpu-mt/torus-40x50/4");
  ASSERT_TRUE(group(plan, "fake-vulkan-method", 2));
  EXPECT_EQ(group(plan, "fake-vulkan-method", 2)->level, 3);
  EXPECT_FALSE(group(plan, "fake-test-scheme", 1));  // test schemes never
  EXPECT_FALSE(group(plan, "fake-cpu-peer", 1));     // CPU schemes are only the rows beside
  // Size 1 of every scheme comes before any size 2: a check cut off halfway has every scheme once;
  // within a size the methods come first.
  const auto first_size2 = std::find_if(plan.groups.begin(), plan.groups.end(), [](const CheckGroup& g) { return g.size == 2; });
  EXPECT_TRUE(std::all_of(first_size2, plan.groups.end(), [](const CheckGroup& g) { return g.size == 2; }));
  EXPECT_LT(method1 - plan.groups.data(), peer1 - plan.groups.data());
}

TEST(GpuCheckPlan, QuickTriesTheDefaultMeshesFirstAndAnUnavailableBackendIsANote) {
  MeasureContext context(MachineInfo{});
  const CheckPlan quick = plan_gpu_check(kGpuCheckQuickBounds, true, {Backend::Vulkan}, context);
  const CheckGroup* peer1 = group(quick, "fake-gpu-peer", 1);
  ASSERT_TRUE(peer1);
  EXPECT_EQ(peer1->mesh, "quadsphere");
  EXPECT_GE(peer1->triangles, kGpuCheckQuickBounds.min);
  EXPECT_LE(peer1->triangles, kGpuCheckQuickBounds.max);
  const CheckPlan none = plan_gpu_check(kGpuCheckBounds, false, {Backend::OpenGl}, context);
  EXPECT_FALSE(group(none, "fake-gpu-peer", 1));
  EXPECT_TRUE(std::any_of(none.notes.begin(), none.notes.end(), [](const std::string& n) {
    return n.find("fake-gpu-peer: left out, its backend (vulkan) is unavailable") != std::string::npos;
  })) << ::testing::PrintToString(none.notes);
}

TEST(GpuCheckLevels, NearestTheTargetWithinBoundsThenFourTimesOrAQuarter) {
  // The sword's 89,512 quads at depths 1-5: depth 3 (11.5 M) is nearest 15 M, depth 4 (45.8 M) the second.
  const std::vector<std::pair<int, long>> depths = {{1, 716'096}, {2, 2'864'384}, {3, 11'457'536}, {4, 45'830'144}, {5, 183'320'576}};
  EXPECT_EQ(check_levels(depths, kGpuCheckBounds), (std::vector<int>{3, 4}));
  // A geometry image whose scheme stops at depth 6 (31.5 M): the second size is a quarter.
  const std::vector<std::pair<int, long>> image = {{4, 1'968'128}, {5, 7'872'512}, {6, 31'490'048}};
  EXPECT_EQ(check_levels(image, kGpuCheckBounds), (std::vector<int>{6, 5}));
  // None within the bounds (a geometry shader's N <= 8 on the sword): the largest, then a quarter of it.
  std::vector<std::pair<int, long>> rates;
  for (int n = 2; n <= 8; ++n) rates.emplace_back(n, 2L * 89'512 * (n - 1) * (n - 1));
  EXPECT_EQ(check_levels(rates, kGpuCheckBounds), (std::vector<int>{8, 5}));
  EXPECT_EQ(check_levels({{3, 20'000'000}}, kGpuCheckBounds), (std::vector<int>{3}));
  EXPECT_TRUE(check_levels({}, kGpuCheckBounds).empty());
}

TEST(GpuCheckMeshes, LargeMeshesElseHeadlinesThenDefaultsAndQuickPutsDefaultsFirst) {
  SchemeInfo i;
  i.default_meshes = {"a", "b"};
  i.headline_runs = {{"h", Backend::Cpu, 4}, {"a", Backend::CpuMt, 4}};
  EXPECT_EQ(check_mesh_candidates(i, false), (std::vector<std::string>{"h", "a", "b"}));
  EXPECT_EQ(check_mesh_candidates(i, true), (std::vector<std::string>{"a", "b", "h"}));
  i.large_meshes = {"big"};
  EXPECT_EQ(check_mesh_candidates(i, false), (std::vector<std::string>{"big", "a", "b"}));
}

RunRow gpu_row(const std::string& scheme, Backend backend, double mtris, long triangles) {
  RunRow r;
  r.scheme = r.spec = scheme;
  r.backend = backend;
  r.mesh = "stein/sword_quad_dominant";
  r.level = 3, r.tessellation = 8, r.triangles = triangles;
  r.triangle_rate_mtris = mtris;
  r.bandwidth_fraction = 0.25;
  return r;
}

ResultsFile check_results(const std::string& vulkan_type, const std::string& opengl_type, int schemes) {
  ResultsFile f;
  f.created = "2026-12-07T00:00:00Z";
  f.machine.git_commit = "abc1234";
  f.machine.cpu_model = "Some CPU with a rather long model name, 2.10 GHz, and more words than fit";
  f.machine.cores = 16;
  f.machine.vulkan_device = vulkan_type == "cpu" ? "llvmpipe (LLVM 15.0.6, 256 bits)" : "NVIDIA H100 80GB HBM3";
  f.machine.vulkan_device_type = vulkan_type;
  f.machine.vulkan_driver = "some driver 1.2.3";
  f.machine.opengl_renderer = opengl_type == "cpu" ? "llvmpipe (LLVM 15.0.6, 256 bits)" : "NVIDIA H100/PCIe/SSE2";
  f.machine.opengl_device_type = opengl_type;
  for (int i = 0; i < schemes; ++i) {
    const std::string name = "geometry-image-" + std::to_string(i);
    f.runs.push_back(gpu_row(name, Backend::Vulkan, 1000.0 + i, 11'457'536));
    f.runs.push_back(gpu_row(name, Backend::Vulkan, 900.0 + i, 45'830'144));  // the slower size
    RunRow cpu = gpu_row(name, Backend::CpuMt, 50, 11'457'536);
    f.runs.push_back(cpu);
    PairedCell c;
    c.mesh = cpu.mesh;
    c.row = {name, Backend::Vulkan, 3, 11'457'536};
    c.peer = {name, Backend::CpuMt, 3, 11'457'536};
    c.rate_ratio_median = 20.0 + i;
    f.paired.push_back(c);
  }
  f.runs.push_back(gpu_row("osd-glcompute-loop", Backend::OpenGl, 9'999, 11'457'536));
  PairedCell peer;
  peer.mesh = "stein/sword_quad_dominant";
  peer.row = {"osd-glcompute-loop", Backend::OpenGl, 3, 11'457'536};
  peer.peer = {"osd-stencil-loop", Backend::CpuMt, 3, 11'457'536};
  peer.rate_ratio_median = 123.45;
  f.paired.push_back(peer);
  return f;
}

bool has(const std::vector<std::string>& lines, const std::string& text) {
  return std::any_of(lines.begin(), lines.end(), [&](const std::string& l) { return l.find(text) != std::string::npos; });
}

TEST(GpuCheckSummary, LavapipeRowsAreLabelledAndNeverRankedAsAGpu) {
  CheckProgress p;
  p.stages = 10, p.ok = 10;
  const auto lines = gpu_check_summary(check_results("cpu", "cpu", 3), p);
  EXPECT_TRUE(has(lines, "llvmpipe (LLVM 15.0.6, 256 bits): a CPU implementation of Vulkan (lavapipe), NOT a GPU"));
  EXPECT_TRUE(has(lines, "a CPU implementation of OpenGL, NOT a GPU"));
  EXPECT_TRUE(has(lines, " vulkan* "));
  EXPECT_TRUE(has(lines, " opengl* "));
  EXPECT_TRUE(has(lines, "not a GPU figure; not ranked"));
  EXPECT_FALSE(has(lines, "fastest"));
  EXPECT_FALSE(has(lines, "GPU target"));
  EXPECT_TRUE(has(lines, "no GPU here: nothing is ranked"));
  // Each scheme's best row (the faster size) with its paired ratio to its own cpu-mt row.
  EXPECT_TRUE(has(lines, "geometry-image-2       vulkan* sword_quad_dominant d=3   11.5   1002.0 0.25 22.00x cpu-mt"))
      << ::testing::PrintToString(lines);
}

TEST(GpuCheckSummary, OnAGpuTheFastestIsNamedAgainstTheTargetButNotASoftwareOpenGlRow) {
  CheckProgress p;
  p.stages = 10, p.ok = 10;
  const auto lines = gpu_check_summary(check_results("discrete", "cpu", 3), p);
  EXPECT_TRUE(has(lines, "Vulkan: NVIDIA H100 80GB HBM3 (discrete GPU)"));
  // osd-glcompute's llvmpipe row is the fastest number but not a GPU's.
  EXPECT_TRUE(has(lines, "GPU target >= 5 G triangles/s: NOT met; fastest: geometry-image-2 (vulkan), 1.00 G/s at 11.5 M"))
      << ::testing::PrintToString(lines);
  EXPECT_TRUE(has(lines, " opengl* "));
  EXPECT_FALSE(has(lines, " vulkan* "));
}

TEST(GpuCheckSummary, FitsOneScreenWithFifteenSchemesAndSaysWhatDidNotRun) {
  CheckProgress p;
  p.stages = 33, p.ok = 25, p.failed = 3, p.cut_off = 1, p.not_run = 4;
  p.budget_s = 540;
  for (int i = 0; i < 4; ++i) p.problems.push_back("size 2: scheme-" + std::to_string(i) + ": failed: exit code 3: " + std::string(200, 'x'));
  p.notes = {"osd-glcompute: left out, its backend (opengl) is unavailable here"};
  p.report = "report generation failed (reports/report.py, exit code 1)";
  const auto lines = gpu_check_summary(check_results("discrete", "gpu", 15), p);
  EXPECT_LE(lines.size(), 15u + 16u) << ::testing::PrintToString(lines);  // 16 schemes
  for (const std::string& l : lines) EXPECT_LE(l.size(), 100u) << l;
  EXPECT_TRUE(has(lines, "123.45x osd-stencil-loop")) << ::testing::PrintToString(lines);
  EXPECT_TRUE(has(lines, "25 of 33 stages ok, 3 failed, 1 cut off, 4 not run"));
  EXPECT_TRUE(has(lines, "`gpu-check --resume` measures what is missing"));
  EXPECT_TRUE(has(lines, "problem: 2 more"));
  EXPECT_TRUE(has(lines, "report: not written: report generation failed"));
  EXPECT_TRUE(has(lines, "note: osd-glcompute: left out"));
}

}  // namespace
}  // namespace sdb
