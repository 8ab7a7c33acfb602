// read_results and read_gate_config on what a hostile or broken file holds (tests/fuzz's findings
// among them): every such file is an InputError naming it, never another exception, undefined
// behaviour or a value the gate cannot judge with.
#include <gtest/gtest.h>

#include "harness/core/errors.h"
#include "harness/core/input_error_of_file.h"
#include "harness/gate/gate.h"
#include "harness/results/results.h"

using namespace sdb;

namespace {

// What `read` says of a JSON file holding `text` (harness/core/input_error_of_file.h).
template <class Reader>
std::string read_error(const std::string& text, Reader read) {
  return input_error_of_file("sdb_readers_test.json", text, read);
}

std::string results_error(const std::string& text) { return read_error(text, read_results); }
std::string gate_error(const std::string& text) { return read_error(text, read_gate_config); }

std::string with_level(const std::string& level) {
  return R"({"schema": 1, "machine": {}, "runs": [{"scheme": "osd-bfr", "backend": "cpu", "mesh": "cube", "level": )" + level +
         "}]}";
}

// A file of one row whose fields `row_fields` (JSON members, after the required ones) set, and of
// paired cells `paired`.
std::string with_row(const std::string& row_fields, const std::string& paired = "[]") {
  return R"({"schema": 1, "machine": {"cpu_model": "x", "cores": 2}, "paired": )" + paired +
         R"(, "runs": [{"scheme": "osd-bfr", "backend": "cpu", "mesh": "cube", "level": 9, "tessellation": 8)" +
         (row_fields.empty() ? "" : ", " + row_fields) + "}]}";
}

std::string cell(const std::string& ratio) {
  return R"([{"mesh": "cube", "scheme": "cpatch-2pass", "backend": "cpu", "level": 9, "triangles": 10, "rounds": 3,
             "peer": {"scheme": "osd-bfr", "backend": "cpu", "level": 9, "triangles": 10},
             "rate_ratio": )" + ratio + R"(, "time_ms": {"median": 1}, "peer_time_ms": {"median": 2}}])";
}

}  // namespace

TEST(ResultsReader, NumberPastDoubleRangeIsMalformedJson) {
  EXPECT_NE(results_error(R"({"schema": 1, "runs": [], "created": 22E517456166666665})").find("malformed JSON"),
            std::string::npos);
}

TEST(ResultsReader, CountsMustBeWholeNumbersInRange) {
  EXPECT_EQ(results_error(with_level("3")), "");
  EXPECT_EQ(results_error(with_level("3.0")), "");
  EXPECT_NE(results_error(with_level("1e300")).find("'level' is not a whole number within range"), std::string::npos);
  EXPECT_NE(results_error(with_level("2147483648")).find("'level'"), std::string::npos);
  EXPECT_NE(results_error(with_level("2.5")).find("'level'"), std::string::npos);
  EXPECT_NE(results_error(with_level("\"three\"")).find("'level' must be a number"), std::string::npos);
}

TEST(ResultsReader, SchemaBeyondIntIsUnknownNotWrapped) {
  // 2^32 + 1 once compared equal to schema 1 after narrowing to int.
  EXPECT_NE(results_error(R"({"schema": 4294967297, "runs": []})").find("unknown results schema 4294967297"),
            std::string::npos);
}

TEST(GateConfigReader, RefusesValuesTheGateCannotJudgeWith) {
  EXPECT_EQ(gate_error(R"({"alpha": 0.01, "min_repetitions": 3, "default_threshold": 0.1})"), "");
  EXPECT_NE(gate_error(R"({"alpha": 1.01})").find("alpha must lie between 0 and 1"), std::string::npos);
  EXPECT_NE(gate_error(R"({"alpha": 0})").find("alpha"), std::string::npos);
  EXPECT_NE(gate_error(R"({"default_threshold": -0.5})").find("threshold must be"), std::string::npos);
  EXPECT_NE(gate_error(R"({"thresholds": [{"match": "x", "threshold": -1}]})").find("threshold must be"), std::string::npos);
  EXPECT_NE(gate_error(R"({"min_repetitions": 0})").find("min_repetitions must be"), std::string::npos);
  EXPECT_NE(gate_error(R"({"min_repetitions": 1e300})").find("min_repetitions must be"), std::string::npos);
  EXPECT_EQ(gate_error(R"({"normalisers": [{"match": "/vulkan/", "backend": "cpu-mt"}]})"), "");
  EXPECT_NE(gate_error(R"({"normalisers": [{"match": "/vulkan/", "backend": "gpu"}]})").find("'gpu' is not a backend"),
            std::string::npos);
  EXPECT_NE(gate_error(R"({"normalisers": [{"match": "(", "backend": "cpu"}]})").find("not a regular expression"),
            std::string::npos);
}

TEST(ResultsReader, RefusesFiguresNoRunCanGiveNamingTheRow) {
  const std::string times = R"("triangles": 10, "time_ms": {"median": 2, "min": 1, "max": 3, "reps": 3, "samples": [1, 2, 3]})";
  EXPECT_EQ(results_error(with_row(times)), "");
  EXPECT_EQ(results_error(with_row(times, cell(R"({"median": 2, "min": 1.5, "max": 2.5, "per_round": [1.5, 2, 2.5]})"))), "");
  // A median outside its own range, a negative time or sample, in rows and in paired cells.
  EXPECT_NE(results_error(with_row(R"("time_ms": {"median": 5, "min": 1, "max": 3, "reps": 3})"))
                .find("runs[0] osd-bfr/cpu/cube/9: time_ms: median 5 outside its own range 1..3"),
            std::string::npos);
  EXPECT_NE(results_error(with_row(R"("time_ms": {"median": 2, "min": 1, "max": 3, "reps": 3, "samples": [1, -2, 3]})"))
                .find("time_ms: a negative sample (-2)"),
            std::string::npos);
  EXPECT_NE(results_error(with_row(times, cell(R"({"median": 9, "min": 1.5, "max": 2.5})")))
                .find("paired[0] cpatch-2pass/cpu/cube/9: rate_ratio: median 9 outside its own range 1.5..2.5"),
            std::string::npos);
  EXPECT_NE(results_error(with_row(times, cell(R"({"median": -2, "min": -3, "max": -1})"))).find("is -2 (a ratio of two rates is positive)"),
            std::string::npos);
  // A rate without triangles, negative counts, cracks past the rays cast.
  EXPECT_NE(results_error(with_row(R"("triangles": 0, "triangle_rate_mtris": 122)")).find("a triangle rate of 122 M/s at 0 triangles"),
            std::string::npos);
  EXPECT_NE(results_error(with_row(R"("watertight": {"open_edges": -7, "rays": 10, "ray_cracks": 0})")).find("watertight.open_edges is -7"),
            std::string::npos);
  EXPECT_NE(results_error(with_row(R"("watertight": {"open_edges": 0, "rays": 10, "ray_cracks": 11})")).find("11 cracked rays of 10"),
            std::string::npos);
  EXPECT_NE(results_error(with_row(R"("triangles": -5)")).find("triangles is negative (-5)"), std::string::npos);
  EXPECT_NE(results_error(with_row(R"("extraordinary_fraction": 1.5)")).find("extraordinary_fraction 1.5 is not a fraction"),
            std::string::npos);
  EXPECT_NE(results_error(with_row(R"("deviation": {"pos_max_pct": 1, "pos_mean_pct": 0.1, "pos_rms_pct": 0.2, "pos_p95_pct": 3,
                                        "pos_max_rel_diag": 0.001, "normal_max_deg": 1, "normal_mean_deg": 0.1, "hausdorff_rel": 0.001})"))
                .find("deviation.pos_p95_pct 3 is past pos_max_pct 1"),
            std::string::npos);
  // NaN (null) is "not measured" and always allowed.
  EXPECT_EQ(results_error(with_row(R"("triangles": 10, "time_ms": {"median": null, "min": null, "max": null, "reps": 0})")), "");
}

TEST(ResultsReader, RefusesAFileWithoutAMachineOrWithARunTwice) {
  EXPECT_NE(results_error(R"({"schema": 1, "runs": []})").find("no 'machine' section"), std::string::npos);
  const std::string row = R"({"scheme": "osd-bfr", "backend": "cpu", "mesh": "cube", "level": 9})";
  EXPECT_NE(results_error(R"({"schema": 1, "machine": {}, "runs": [)" + row + ", " + row + "]}")
                .find("runs[1] osd-bfr/cpu/cube/9: the run's second row (the first is runs[0])"),
            std::string::npos);
}
