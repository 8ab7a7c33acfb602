// README.md's figures held to what the code does: the row counts of the quick and default sets as
// `run` plans them (make_plan, with every scheme `subdivbench` links), and the READMEs' sizes (a
// README is a map: README.md at most 12 KB, a scheme's at most 15 KB; dated measurements go to
// notes/). A figure is marked in README.md as <!-- plan-rows:SET -->N<!-- /plan-rows -->.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "datasets/manifest.h"
#include "harness/bench/machine.h"
#include "harness/run/plan.h"

namespace sdb {
namespace {

namespace fs = std::filesystem;

std::string read_file(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The figure README.md gives for `set` ("1,954" read as 1954); -1 when there is none.
long readme_rows(const std::string& readme, const std::string& set) {
  const std::regex marked("<!-- plan-rows:" + set + " -->([0-9,]+)<!-- /plan-rows -->");
  std::smatch m;
  if (!std::regex_search(readme, m, marked)) return -1;
  std::string digits = m[1];
  std::erase(digits, ',');
  return std::stol(digits);
}

size_t planned_rows(bool quick) {
  MeasureContext context(describe_machine(false));
  Selection selection;
  selection.quick = quick;
  return make_plan(selection, context).runs.size();
}

// The README states its figures for a machine with the corpus, a Vulkan device and an OpenGL
// context (lavapipe and llvmpipe in CI); elsewhere the plan is smaller, and this says why.
std::string missing_for_the_readme() {
  if (!corpus_dir()) return "the shared corpus is not beside the checkout";
  const auto backends = available_backends();
  for (Backend b : {Backend::Vulkan, Backend::OpenGl})
    if (std::find(backends.begin(), backends.end(), b) == backends.end())
      return "the " + std::string(to_string(b)) + " backend is unavailable here";
  return "";
}

TEST(ReadmeFigures, TheQuickAndDefaultSetsPlanTheRowsTheReadmeSays) {
  const std::string readme = read_file(fs::path(SDB_SOURCE_DIR) / "README.md");
  const long quick = readme_rows(readme, "quick"), full = readme_rows(readme, "default");
  ASSERT_GT(quick, 0) << "README.md marks no quick-set row count (<!-- plan-rows:quick -->N<!-- /plan-rows -->)";
  ASSERT_GT(full, 0) << "README.md marks no default-set row count (<!-- plan-rows:default -->N<!-- /plan-rows -->)";
  if (const std::string why = missing_for_the_readme(); !why.empty()) GTEST_SKIP() << why;
  EXPECT_EQ(size_t(quick), planned_rows(true)) << "README.md's quick-set rows differ from `run --quick`'s plan";
  EXPECT_EQ(size_t(full), planned_rows(false)) << "README.md's default-set rows differ from `run`'s plan";
}

TEST(ReadmeFigures, ReadmesAreMapsNotLogs) {
  const fs::path root(SDB_SOURCE_DIR);
  EXPECT_LE(fs::file_size(root / "README.md"), 12u * 1024) << "README.md: move detail to the folders' READMEs";
  int schemes = 0;
  for (const auto& folder : fs::directory_iterator(root / "schemes")) {
    const fs::path readme = folder.path() / "README.md";
    if (!folder.is_directory() || !fs::exists(readme)) continue;
    ++schemes;
    EXPECT_LE(fs::file_size(readme), 15u * 1024) << readme << ": move dated measurements to its notes/";
  }
  EXPECT_GT(schemes, 0);
  std::printf("README.md and %d scheme READMEs checked\n", schemes);
}

}  // namespace
}  // namespace sdb
