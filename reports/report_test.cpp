// `subdivbench report` end to end on the fixtures under reports/testdata: what the summary says,
// the history view, and bad input (one line naming the file, exit 2, an earlier report intact).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include "tests/cli_helpers.h"

namespace fs = std::filesystem;
using sdb::test::run_cli;
using sdb::test::slurp;

namespace {

const fs::path kData = fs::path(SDB_SOURCE_DIR) / "reports" / "testdata";

fs::path fresh_folder(const std::string& name) {
  const fs::path dir = fs::path(SDB_BINARY_DIR) / "report-test" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string report_args(const std::vector<fs::path>& inputs, const fs::path& out, const std::string& extra = "") {
  std::string args = "report";
  for (const auto& in : inputs) args += " --in " + in.string();
  return args + " --out " + out.string() + " " + extra;
}

int lines(const std::string& text) { return static_cast<int>(std::count(text.begin(), text.end(), '\n')); }

bool has_work_folder(const fs::path& dir) {
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.path().filename().string().rfind(".report-", 0) == 0) return true;
  return false;
}

TEST(Report, SummaryComesFirstWithPairedAndSinglePassRatios) {
  const fs::path out = fresh_folder("summary");
  const auto r = run_cli(report_args({kData / "sample" / "results.json"}, out, "--paper " + (kData / "paper" / "table.md").string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string html = slurp(out / "report.html");
  const size_t summary = html.find("id='summary'"), rows = html.find("id='all-rows'");
  ASSERT_NE(summary, std::string::npos);
  ASSERT_NE(rows, std::string::npos);
  EXPECT_LT(summary, html.find("id='plots'"));
  EXPECT_LT(summary, rows);
  EXPECT_NE(html.find("id='summary-matrix-cpu'"), std::string::npos);
  // A paired cell prints its rounds and range; an unpaired one says it is a single pass.
  EXPECT_TRUE(std::regex_search(html, std::regex("[0-9.]+&ndash;[0-9.]+, 5 rounds"))) << "paired range missing";
  EXPECT_NE(html.find("single pass"), std::string::npos);
  // The done-when sentence: per mesh, the fastest scheme per backend and its ratio to its peer.
  EXPECT_TRUE(std::regex_search(html, std::regex("on cpu [a-z0-9:=-]+ is fastest \\([0-9.]+ M triangles/s")));
  EXPECT_NE(html.find("class='picture-shaded'"), std::string::npos);
  EXPECT_NE(html.find("shaded picture not made: vkQueueSubmit: VK_ERROR_DEVICE_LOST"), std::string::npos);
  EXPECT_NE(html.find("class='paper'"), std::string::npos);
  // The machine line gives the Vulkan device's two write figures: the fill that bandwidth
  // fractions divide by, and what a shader that only stores reaches.
  EXPECT_NE(html.find("buffer fill 6.4 GB/s, a store-only shader 2.1 GB/s"), std::string::npos);
  EXPECT_EQ(html.find("http://"), std::string::npos) << "nothing may be fetched";
  EXPECT_EQ(html.find("https://"), std::string::npos) << "nothing may be fetched";
  EXPECT_TRUE(fs::exists(out / "plots" / "cost_growth.png"));
  const std::string md = slurp(out / "report.md");
  EXPECT_NE(md.find("### Fastest per mesh"), std::string::npos);
  // A paired cell's rate is the paired rounds' (the fixture's geometry-image on quadsphere: 10 M
  // triangles/s there, 29.6 in its single pass).
  EXPECT_NE(md.find("| 10 Mtri/s, 14.19x (14.02-16.35, 5 rounds) |"), std::string::npos) << md;
  // A backend cell (a GPU row against its own scheme's cpu-mt row) has its own lines and leaves
  // the vulkan cell's ratio to its peer alone.
  EXPECT_NE(md.find("### GPU against the same scheme's CPU"), std::string::npos) << md;
  EXPECT_NE(md.find("- **cpatch-2pass**: quadsphere vulkan 0.029x of cpu-mt (range 0.028-0.031, 5 rounds;"), std::string::npos)
      << md;
  EXPECT_NE(html.find("<h3>GPU against the same scheme's CPU</h3>"), std::string::npos);
  EXPECT_EQ(md.find("0.03x cpatch-2pass"), std::string::npos) << "a backend cell read as the peer ratio";
  EXPECT_FALSE(has_work_folder(out));
}

TEST(Report, ASchemeWhosePeerDidNotRunIsNotCalledTheAnchor) {
  // cpatch-2pass's rows alone (reports/testdata/no_peer): its peer, osd-bfr, has no row.
  const fs::path out = fresh_folder("no_peer");
  const auto r = run_cli(report_args({kData / "no_peer" / "results.json"}, out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string html = slurp(out / "report.html"), md = slurp(out / "report.md");
  EXPECT_NE(html.find("<div class='ratio range'>no peer row</div>"), std::string::npos);
  EXPECT_EQ(html.find("<div class='ratio range'>anchor</div>"), std::string::npos) << "cpatch-2pass is no anchor";
  EXPECT_NE(md.find("Mtri/s, no peer row"), std::string::npos) << md;
}

TEST(Report, SaysPerSchemeAndMeshWhetherItReproducesTheInputsLimitOrHowCloselyItApproximatesIt) {
  // reports/testdata/limits: geometry-image approximating by nearest points, osd-uniform planted
  // approximating at depth 2 only (a crease still active there), fragments-cc reproducing.
  const fs::path out = fresh_folder("limits");
  const auto r = run_cli(report_args({kData / "limits" / "results.json"}, out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string html = slurp(out / "report.html"), md = slurp(out / "report.md");
  EXPECT_NE(html.find("id='limit-matrix'"), std::string::npos);
  for (const std::string& text : {std::string("approximates: max 0.16%, p95 0.045%, by nearest points"),
                                  std::string("approximates: max 0.024%, p95 0.011% (at level 2; reproduces at the others)"),
                                  std::string("<td>reproduces</td>")}) {
    EXPECT_NE(html.find(text), std::string::npos) << text;
  }
  EXPECT_NE(md.find("## Against the input's limit surface"), std::string::npos) << md;
  EXPECT_NE(md.find("| fragments-cc | reproduces |"), std::string::npos) << md;
  EXPECT_NE(md.find("| geometry-image | approximates: max 0.16%, p95 0.045%, by nearest points |"), std::string::npos) << md;
  // The approximating osd-uniform row has no bound to fail, and geometry-image's own bound (on its
  // g0) is kept: no chip is red.
  EXPECT_EQ(html.find("class='chip bad' title="), std::string::npos);
  EXPECT_NE(html.find("class='chip good' title="), std::string::npos);
}

TEST(Report, SaysWhyThereAreNoPictures) {
  const fs::path out = fresh_folder("no-pictures");
  fs::create_directories(out / "pictures");
  std::ofstream(out / "pictures" / "pictures.json")
      << R"json({"schema": 1, "available": false, "reason": "no Vulkan device (no ICD found)", "pictures": []})json";
  const auto r = run_cli(report_args({kData / "sample" / "results.json"}, out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string html = slurp(out / "report.html");
  EXPECT_NE(html.find("No pictures: no Vulkan device (no ICD found)."), std::string::npos);
  EXPECT_EQ(html.find("class='picture-shaded'"), std::string::npos);
}

TEST(Report, MergesShardsOfOneSweep) {
  const fs::path out = fresh_folder("shards");
  const auto r = run_cli(report_args({kData / "shards" / "shard0.json", kData / "shards" / "shard1.json"}, out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string html = slurp(out / "report.html");
  EXPECT_NE(html.find("merged from 2 files (shards of 2, all present)"), std::string::npos);
  // One shard alone is not the whole sweep, and the report says so.
  const fs::path part = fresh_folder("one-shard");
  ASSERT_EQ(run_cli(report_args({kData / "shards" / "shard0.json"}, part)).exit_code, 0);
  EXPECT_NE(slurp(part / "report.html").find("Part of a sweep only: merged from 1 file (shards of 2; MISSING: 1)"),
            std::string::npos);
}

TEST(Report, HistoryOverThreeCommitsRenders) {
  const fs::path out = fresh_folder("history");
  const fs::path h = kData / "history";
  const auto r = run_cli(report_args({h / "a.json", h / "b.json", h / "c.json"}, out, "--history"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string html = slurp(out / "report.html");
  for (const char* commit : {"aaaaaaa", "bbbbbbb", "ccccccc"}) EXPECT_NE(html.find(commit), std::string::npos) << commit;
  EXPECT_TRUE(fs::exists(out / "plots" / "history.png"));
  // c.json planted cpatch-2pass 60% slower against its peer, round by round: the gate's verdict.
  EXPECT_TRUE(std::regex_search(html, std::regex("<td class='num slower'[^>]*>[0-9.]+ <span class='range'>\\+[56][0-9]%")))
      << "the planted slowdown is not marked";
  const std::string md = slurp(out / "report.md");
  EXPECT_NE(md.find("| cpatch-2pass/cpu/frog-standin/9 | osd-bfr, paired |"), std::string::npos) << md;
}

// reports/testdata/history/vulkan: a Vulkan row's kernel twice as slow from a to b; from b to c its
// cpu-mt row (its normaliser in ci/gate.json) and its kernel both twice as slow. `report --history`
// must say of every benchmark at every commit what `gate` says of the same pair of files.
TEST(Report, HistoryGivesTheGatesVerdictOnEveryPairVulkanRowsIncluded) {
  const fs::path out = fresh_folder("history-vulkan"), h = kData / "history" / "vulkan";
  const std::vector<fs::path> files = {h / "a.json", h / "b.json", h / "c.json"};
  const auto r = run_cli(report_args(files, out, "--history"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string md = slurp(out / "report.md");
  std::map<std::string, std::vector<std::string>> history;  // benchmark -> verdict per step
  const std::regex cell("\\(([+-][0-9]+%), (slower|faster|same)\\)");
  std::istringstream lines_of(md);
  for (std::string line; std::getline(lines_of, line);) {
    if (line.rfind("| ", 0) != 0 || line.find(" | ") == std::string::npos) continue;
    const std::string name = std::regex_replace(line.substr(2, line.find(" | ") - 2), std::regex("\\\\_"), "_");
    for (std::sregex_iterator m(line.begin(), line.end(), cell), end; m != end; ++m) history[name].push_back((*m)[2]);
  }
  int compared = 0;
  for (size_t i = 1; i < files.size(); ++i) {
    const auto g = run_cli("gate --baseline " + files[i - 1].string() + " --current " + files[i].string());
    std::istringstream table(g.out);
    for (std::string line; std::getline(table, line);) {
      std::smatch m;
      if (!std::regex_search(line, m, std::regex("^(\\S+/\\S+/\\S+/[0-9]+) .* (same|REGRESSION|improvement)$"))) continue;
      const std::string gate = m[2] == "REGRESSION" ? "slower" : m[2] == "same" ? "same" : "faster";
      ASSERT_GE(history[m[1]].size(), i) << m[1] << "\n" << md;
      EXPECT_EQ(history[m[1]][i - 1], gate) << m[1] << " at " << files[i];
      ++compared;
    }
  }
  std::printf("history: %d verdicts compared with the gate's\n", compared);
  EXPECT_EQ(compared, 2 * 16);
  EXPECT_EQ(history["cpatch-2pass/vulkan/frog-standin/9"], (std::vector<std::string>{"slower", "same"})) << md;
  EXPECT_NE(md.find("| cpatch-2pass/vulkan/frog-standin/9 | cpatch-2pass/cpu-mt, paired |"), std::string::npos) << md;
}

// A good report first; then the bad input must leave it exactly as it was.
struct BadInput {
  std::string name;
  std::vector<fs::path> inputs;
  fs::path named;  // the file the one line must name
  std::string extra = "";
};

void PrintTo(const BadInput& bad, std::ostream* os) { *os << bad.name; }

class ReportRefuses : public testing::TestWithParam<BadInput> {};

TEST_P(ReportRefuses, OneLineNamingTheFileAndTheEarlierReportUntouched) {
  const BadInput& bad = GetParam();
  const fs::path out = fresh_folder("bad-" + bad.name);
  ASSERT_EQ(run_cli(report_args({kData / "sample" / "results.json"}, out)).exit_code, 0);
  const std::string before = slurp(out / "report.html"), plots_before = slurp(out / "plots" / "rate.png");
  const auto time_before = fs::last_write_time(out / "report.html");

  const auto r = run_cli(report_args(bad.inputs, out, bad.extra));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(bad.named.string()), std::string::npos) << r.err;
  EXPECT_EQ(slurp(out / "report.html"), before);
  EXPECT_EQ(fs::last_write_time(out / "report.html"), time_before);
  EXPECT_EQ(slurp(out / "plots" / "rate.png"), plots_before);
  EXPECT_FALSE(has_work_folder(out));
}

const fs::path kBad = kData / "bad";
INSTANTIATE_TEST_SUITE_P(
    BadInputs, ReportRefuses,
    testing::Values(
        BadInput{"other-schema", {kData / "sample" / "results.json", kBad / "other-schema.json"}, kBad / "other-schema.json"},
        BadInput{"truncated", {kBad / "truncated.json"}, kBad / "truncated.json"},
        BadInput{"other-commit", {kData / "shards" / "shard0.json", kBad / "shard1-other-commit.json"},
                 kBad / "shard1-other-commit.json"},
        BadInput{"same-shard-twice", {kData / "shards" / "shard0.json", kBad / "shard0-again.json"}, kBad / "shard0-again.json"},
        BadInput{"missing-paper", {kData / "sample" / "results.json"}, kBad / "no-such-table.md",
                 "--paper " + (kBad / "no-such-table.md").string()},
        BadInput{"bad-pictures", {kBad / "pictures-malformed" / "results.json"}, kBad / "pictures-malformed" / "pictures" / "pictures.json"},
        BadInput{"picture-outside", {kBad / "pictures-escape" / "results.json"}, kBad / "pictures-escape" / "pictures" / "pictures.json"}),
    [](const testing::TestParamInfo<BadInput>& param) {
      std::string n = param.param.name;
      std::replace(n.begin(), n.end(), '-', '_');
      return n;
    });

TEST(Report, AllowMixedMergesOtherCommits) {
  const fs::path out = fresh_folder("mixed");
  const auto r = run_cli(report_args({kData / "shards" / "shard0.json", kBad / "shard1-other-commit.json"}, out, "--allow-mixed"));
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

}  // namespace

namespace {

// Unescaped | in a Markdown table line: its cell boundaries.
int table_bars(const std::string& line) {
  int bars = 0;
  for (size_t i = 0; i < line.size(); ++i) bars += line[i] == '|' && (i == 0 || line[i - 1] != '\\');
  return bars;
}

std::string hostile_row(const std::string& scheme, const std::string& mesh, const std::string& peer) {
  const std::string peer_fields = peer.empty() ? "" : R"("peer": ")" + peer + R"(", "peer_backend": "cpu", )";
  return R"({"scheme": ")" + scheme + R"(", "spec": ")" + scheme + R"(", "role": "method", "backend": "cpu", "mesh": )" +
         mesh + R"(, "level": 9, "tessellation": 8, "triangles": 1000, "vertices": 500, )" + peer_fields +
         R"("time_ms": {"median": 1, "min": 1, "max": 1, "reps": 1, "samples": [1]}, "triangle_rate_mtris": 1,
            "watertight": {"open_edges": 0, "rays": 10, "ray_cracks": 0, "seed": 1}, "status": "ok", "message": "ok"})";
}

}  // namespace

// Issue 40: mesh names are data. A mesh file named <img src=x onerror=alert(1)>.obj must not become
// markup in report.html or report.md, and pi|pe.obj must not break a Markdown table.
TEST(Report, EscapesWhatComesFromData) {
  const fs::path out = fresh_folder("escaping");
  const std::vector<std::string> meshes = {R"("<img src=x onerror=alert(1)>.obj")", R"("pi|pe_*x*.obj")"};
  std::string rows;
  for (const std::string& m : meshes)
    rows += (rows.empty() ? "" : ", ") + hostile_row("osd-bfr", m, "") + ", " + hostile_row("cpatch-2pass", m, "osd-bfr");
  std::ofstream(out / "results.json") << R"({"schema": 1, "machine": {"cpu_model": "x", "cores": 2}, "runs": [)" << rows << "]}";
  const auto r = run_cli(report_args({out / "results.json"}, out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string html = slurp(out / "report.html"), md = slurp(out / "report.md");
  EXPECT_EQ(html.find("<img src=x"), std::string::npos) << "a mesh name became markup in report.html";
  EXPECT_NE(html.find("&lt;img src=x onerror=alert(1)&gt;.obj"), std::string::npos);
  EXPECT_EQ(md.find("<img src=x"), std::string::npos) << "a mesh name became markup in report.md";
  EXPECT_NE(md.find("&lt;img src=x onerror=alert(1)&gt;.obj"), std::string::npos);
  // Every table line has as many cell boundaries as its header.
  int checked = 0, header = 0;
  std::istringstream lines(md);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("| mesh |", 0) == 0 || line.rfind("| scheme |", 0) == 0) header = table_bars(line);
    else if (line.rfind("|", 0) == 0 && line.find("pi") != std::string::npos) {
      EXPECT_EQ(table_bars(line), header) << line;
      EXPECT_NE(line.find("pi\\|pe\\_\\*x\\*.obj"), std::string::npos) << line;
      ++checked;
    } else if (line.empty()) header = 0;
  }
  EXPECT_EQ(checked, 3) << "the pi|pe rows of the cpu matrix and of every row's table:\n" << md;
}

// Issue 40: the report replaces its own plots, file by file: a file of the user's in DIR/plots stays.
TEST(Report, KeepsTheUsersFilesInThePlotsFolder) {
  const fs::path out = fresh_folder("users-plots");
  fs::create_directories(out / "plots");
  std::ofstream(out / "plots" / "mine.png") << "my plot";
  ASSERT_EQ(run_cli(report_args({kData / "sample" / "results.json"}, out)).exit_code, 0);
  ASSERT_EQ(run_cli(report_args({kData / "sample" / "results.json"}, out)).exit_code, 0);
  EXPECT_EQ(slurp(out / "plots" / "mine.png"), "my plot");
  EXPECT_TRUE(fs::exists(out / "plots" / "rate.png"));
}
