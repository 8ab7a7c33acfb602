#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tests/cli_helpers.h"

namespace fs = std::filesystem;
using sdb::test::run_cli;

namespace {

fs::path write_file(const std::string& name, const std::string& text) {
  const fs::path p = fs::temp_directory_path() / "sdb_cli_inputs" / name;
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
  return p;
}

}  // namespace

// Bad input: one line on stderr naming file and line, exit code 2, nothing on stdout.
TEST(Cli, BadInputExitsTwoWithOneLine) {
  const std::string q = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
  struct Case {
    std::string file, text, expect;
  };
  const std::vector<Case> cases = {
      {"number.obj", "v 0 0 0\nv 1 zz 0\n", "number.obj:2: malformed number 'zz'"},
      {"range.obj", q + "f 1 2 3 5\n", "range.obj:5: vertex index 5 out of range"},
      {"short.obj", q + "f 1 2\n", "short.obj:5: face has 2 vertices"},
      {"nan.obj", "v 0 0 nan\n" + q + "f 1 2 3\n", "nan.obj:1: NaN or Inf coordinate"},
      {"empty.obj", "", "empty.obj: empty mesh: no vertices"},
      {"range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "range.off:6: vertex index 3 out of range"},
      {"mesh.stl", "solid x\n", "mesh.stl: unknown mesh format '.stl'"},
  };
  for (const auto& c : cases) {
    const fs::path p = write_file(c.file, c.text);
    const auto r = run_cli("info " + p.string());
    EXPECT_EQ(r.exit_code, 2) << c.file;
    EXPECT_NE(r.err.find(c.expect), std::string::npos) << c.file << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << c.file << ": " << r.err;
    EXPECT_TRUE(r.out.empty()) << c.file;
  }
  const auto missing = run_cli("info /no/such/file.obj");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("/no/such/file.obj: no such file"), std::string::npos);
  const auto unknown = run_cli("info not-a-mesh");
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_EQ(run_cli("frobnicate").exit_code, 2);
}

TEST(Cli, InfoJsonHasTheFactsInSnakeCase) {
  const auto r = run_cli("info torus-4x6 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* key : {"\"vertices\": 24", "\"faces\": 24", "\"genus\": 1", "\"closed\": true",
                          "\"extraordinary_quad_fraction\": 0.0", "\"euler_characteristic\": 0"})
    EXPECT_NE(r.out.find(key), std::string::npos) << key << "\n" << r.out;
}

TEST(Cli, ListMeshesShowsBuiltinsAndCorpus) {
  const auto r = run_cli("list meshes");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("frog-standin"), std::string::npos);
  EXPECT_NE(r.out.find("torus"), std::string::npos);
  EXPECT_EQ(r.out.find("unreadable"), std::string::npos) << r.out;
  if (fs::exists(fs::path(SDB_SOURCE_DIR) / ".." / "shared" / "datasets")) {
    EXPECT_NE(r.out.find("crane/spot_control"), std::string::npos);
  }
}

// Missing Vulkan means the backend is reported unavailable, not a failure.
TEST(Cli, ListBackendsWithoutAVulkanDriverIsNotAnError) {
  const auto r = run_cli("list backends", "VK_ICD_FILENAMES=/nonexistent");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("vulkan   unavailable  no Vulkan device"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("cpu      available"), std::string::npos) << r.out;
}

// The opengl backend (OpenSubdiv's GL compute peer): a headless EGL context where one can be made,
// else reported unavailable with the reason, exit 0; its rows run where it is available.
TEST(Cli, OpenGlBackendRunsOrIsReportedUnavailable) {
  const auto none = run_cli("list backends", "__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json");
  ASSERT_EQ(none.exit_code, 0) << none.err;
  EXPECT_NE(none.out.find("opengl   unavailable"), std::string::npos) << none.out;
  const auto r = run_cli("list backends");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  if (r.out.find("opengl   available") == std::string::npos) GTEST_SKIP() << "no OpenGL context here:\n" << r.out;
  const auto row = run_cli("validate --scheme osd-glcompute --mesh pole8 --level 2 --backend opengl --rays 20000 --json");
  ASSERT_EQ(row.exit_code, 0) << row.err;
  for (const char* key : {"\"backend\": \"opengl\"", "\"ray_cracks\": 0", "\"open_edges\": 0", "\"status\": \"ok\"",
                          "\"gpu_time_ms\"", "GLComputeEvaluator::EvalStencils", "\"peer\": \"osd-stencil\""})
    EXPECT_NE(row.out.find(key), std::string::npos) << key << "\n" << row.out;
  const auto cpu = run_cli("validate --scheme osd-glcompute --mesh pole8 --level 2 --backend cpu");
  EXPECT_EQ(cpu.exit_code, 2) << "a backend the scheme does not declare is bad usage";
  EXPECT_NE(cpu.err.find("osd-glcompute runs on opengl only"), std::string::npos) << cpu.err;
}

// A scheme that cannot take a mesh refuses it with the file and line, exit code 2.
TEST(Cli, SchemeRefusesNonManifoldMeshWithFileAndLine) {
  const fs::path p = write_file("fan.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n");
  const auto r = run_cli("validate --scheme embree-subdiv --mesh " + p.string() + " --level 3");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("fan.obj:8: non-manifold edge (1,2) shared by 3 faces; embree-subdiv needs"), std::string::npos) << r.err;
  const fs::path d = write_file("degenerate.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 4 3\nf 1 3 3 2\n");
  const auto r2 = run_cli("validate --scheme embree-subdiv --mesh " + d.string() + " --level 3");
  EXPECT_EQ(r2.exit_code, 2);
  EXPECT_NE(r2.err.find("degenerate.obj:6: vertex 3 repeated in one face"), std::string::npos) << r2.err;
}

TEST(Cli, ValidateJsonIsAResultsRow) {
  const auto r = run_cli("validate --scheme osd-bfr --mesh torus-8x8 --level 5 --rays 20000 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* key : {"\"scheme\": \"osd-bfr\"", "\"ray_cracks\": 0", "\"open_edges\": 0", "\"rays\": 40000",
                          "\"pos_max_pct\"", "\"status\": \"ok\"", "\"tessellation\": 4"})
    EXPECT_NE(r.out.find(key), std::string::npos) << key << "\n" << r.out;
}

TEST(Cli, ValidateOfALevelTheSchemeDeclinesIsBadUsage) {
  const auto r = run_cli("validate --scheme osd-bfr --mesh cube --level 1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("osd-bfr/cpu/cube/1: rate N must be 2..129"), std::string::npos) << r.err;
  const auto b = run_cli("validate --scheme osd-uniform --mesh cube --level 2 --backend cpu-mt");
  EXPECT_EQ(b.exit_code, 2);
  EXPECT_NE(b.err.find("one thread only"), std::string::npos) << b.err;
}

// A run named with --run that the harness refuses up front (here past the size limit) is said
// with its reason before the others are measured, not found missing after they ran: nothing is
// timed, nothing written.
TEST(Cli, BenchRefusesAnOversizedNamedRunBeforeMeasuringTheOthers) {
  const fs::path out = fs::temp_directory_path() / ("sdb_bench_refused_" + std::to_string(::getpid()));
  fs::remove_all(out);
  const auto r = run_cli("bench --run osd-uniform/cpu/torus-8x8/1 --run osd-uniform/cpu/quadsphere-64/8 --rounds 1 --out " +
                         out.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("osd-uniform/cpu/quadsphere-64/8: a run of about 3.22e+09 output triangles needs about"),
            std::string::npos) << r.err;
  EXPECT_EQ(r.out.find("osd-uniform/cpu/torus-8x8/1"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(out / "results.json"));
}

// Issue 42: `run` without a selection is the quick set (README, "The quick set"), `--full` the
// default set, and `--plan` counts them without measuring or writing anything.
TEST(Cli, RunWithoutASelectionPlansTheQuickSetAndFullTheDefaultSet) {
  const auto quick = run_cli("run --plan");
  ASSERT_EQ(quick.exit_code, 0) << quick.err;
  EXPECT_NE(quick.out.find("quick set: "), std::string::npos) << quick.out;
  const auto full = run_cli("run --full --plan");
  ASSERT_EQ(full.exit_code, 0) << full.err;
  EXPECT_NE(full.out.find("default set: "), std::string::npos) << full.out;
  const auto rows = [](const std::string& out) {
    const size_t at = out.find(" set: ");
    return at == std::string::npos ? 0L : std::stol(out.substr(at + 6));
  };
  EXPECT_GT(rows(full.out), rows(quick.out)) << quick.out << full.out;
  const auto selected = run_cli("run --scheme osd-uniform --mesh cube --plan");
  ASSERT_EQ(selected.exit_code, 0) << selected.err;
  EXPECT_NE(selected.out.find("selection: "), std::string::npos) << selected.out;
  EXPECT_EQ(run_cli("run --quick --full --plan").exit_code, 2) << "--quick and --full exclude each other";
}
