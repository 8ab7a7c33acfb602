// `subdivbench paper ID --quick` for the c-patch paper's tables: exit code 0, the Markdown written
// with the paper's figures beside ours (subdivbench is run as a user would).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "tests/cli_helpers.h"

namespace {

struct Expectation {
  std::string id;
  std::vector<std::string> contains;  // the paper's figures and our columns
};

TEST(PaperTables, QuickRunOfEachTableWritesItsMarkdown) {
  namespace fs = std::filesystem;
  const fs::path out = fs::temp_directory_path() / ("sdb_cpatch_paper_" + std::to_string(::getpid()));
  const Expectation expectations[] = {
      {"ni2008-table4", {"Sword (140, 138, 38%)", "| 965 / ", "osd-bfr", "Device:"}},
      {"ni2008-table5", {"Head (602, 600, 100%)", "| 389 / ", "the largest N is", "Device:"}},
      {"ni2008-fig12", {"Sword stand-in", "position max %", "normal max"}}};
  for (const Expectation& e : expectations) {
    const sdb::test::CliResult r = sdb::test::run_cli("paper " + e.id + " --quick --out " + out.string());
    EXPECT_EQ(r.exit_code, 0) << e.id << ": " << r.err;
    const std::string markdown = sdb::test::slurp(out / (e.id + ".md"));
    EXPECT_NE(markdown.find("# " + e.id), std::string::npos) << e.id;
    for (const std::string& text : e.contains) EXPECT_NE(markdown.find(text), std::string::npos) << e.id << ": " << text;
  }
  fs::remove_all(out);
}

}  // namespace
