// read_results and read_gate_config on what a hostile or broken file holds (tests/fuzz's findings
// among them): every such file is an InputError naming it, never another exception, undefined
// behaviour or a value the gate cannot judge with.
#include <gtest/gtest.h>

#include "harness/bench/gate.h"
#include "harness/bench/results.h"
#include "harness/core/errors.h"
#include "harness/core/input_error_of_file.h"

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
  return R"({"schema": 1, "runs": [{"scheme": "osd-bfr", "backend": "cpu", "mesh": "cube", "level": )" + level + "}]}";
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
