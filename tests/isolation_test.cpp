// Crash isolation end to end: a row whose code dies of a signal (planted in the test scheme,
// bilinear-limit:crash=N, through subdivbench-testing) becomes a "failed" row naming the signal
// and the stage, the other rows run, and results.json and the report are complete.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>

#include "tests/cli_helpers.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

sdb::test::CliResult run_testing(const std::string& args) { return sdb::test::run_cli(args, "", "subdivbench-testing"); }

const std::string kRow = "--mesh cube --level 3 --backend cpu --reps 1 --rays 1000";

}  // namespace

TEST(Isolation, APlantedCrashFailsItsRowNamingTheSignalAndTheRunGoesOn) {
  const fs::path dir = fs::temp_directory_path() / ("sdb_isolation_" + std::to_string(getpid()));
  fs::remove_all(dir);
  const auto r = run_testing("run --scheme bilinear-limit:crash=2 --scheme bilinear-limit --scheme bilinear-limit:crash=3 " +
                             kRow + " --out " + dir.string());
  EXPECT_EQ(r.exit_code, 1) << "a failed row: exit code 1\n" << r.out << r.err;
  const json runs = json::parse(sdb::test::slurp(dir / "results.json")).at("runs");
  ASSERT_EQ(runs.size(), 3u) << runs.dump(1);
  const json &segv = runs[0], &ok = runs[1], &abort = runs[2];
  EXPECT_EQ(segv.at("spec"), "bilinear-limit:crash=2");
  EXPECT_EQ(segv.at("status"), "failed");
  EXPECT_NE(segv.at("message").get<std::string>().find("crashed during execute: killed by signal 11 (SIGSEGV, Segmentation fault)"),
            std::string::npos)
      << segv.dump();
  EXPECT_EQ(segv.at("mesh_faces"), 6) << "the row as described before the crash";
  EXPECT_EQ(abort.at("status"), "failed");
  EXPECT_NE(abort.at("message").get<std::string>().find("crashed during prepare: killed by signal 6 (SIGABRT, Aborted)"),
            std::string::npos)
      << abort.dump();
  EXPECT_EQ(ok.at("status"), "ok") << ok.dump();
  EXPECT_GT(ok.at("triangles").get<long>(), 0);
  EXPECT_EQ(ok.at("watertight").at("open_edges"), 0);
  EXPECT_GT(ok.at("time_ms").at("median").get<double>(), 0.0);
  EXPECT_NE(r.out.find("FAILED: crashed during execute"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(dir / "report.md")) << "the report of a run with crashed rows is written too";
  EXPECT_NE(sdb::test::slurp(dir / "report.md").find("crashed during prepare"), std::string::npos);
}

// --in-process keeps every row in the one process (profilers, debuggers): the planted crash then
// ends the run, which is how the option is known to take effect.
TEST(Isolation, InProcessRunsAreNotIsolated) {
  const fs::path dir = fs::temp_directory_path() / ("sdb_isolation_inproc_" + std::to_string(getpid()));
  const auto r = run_testing("run --scheme bilinear-limit:crash=2 " + kRow + " --out " + dir.string() + " --in-process");
  // The shell reports a death by SIGSEGV as 139, or hands on the signal itself when it exec'ed.
  EXPECT_TRUE(r.exit_code == 128 + 11 || r.exit_code == -1) << r.exit_code << "\n" << r.out << r.err;
  EXPECT_EQ(r.out.find("wrote"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(dir / "results.json"));
}
