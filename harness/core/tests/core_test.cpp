// The contract's own pieces: names that are part of the results contract, levels, parameters.
#include <gtest/gtest.h>

#include "harness/core/backend.h"
#include "harness/core/errors.h"
#include "harness/core/parameters.h"
#include "harness/core/run_status.h"
#include "harness/core/scheme.h"

using namespace sdb;

TEST(Names, BackendsAndStatusesRoundTrip) {
  for (Backend b : all_backends()) EXPECT_EQ(parse_backend(to_string(b)), b);
  EXPECT_EQ(to_string(Backend::CpuMt), "cpu-mt");
  EXPECT_FALSE(parse_backend("gpu").has_value());
  for (RunStatus s : {RunStatus::Ok, RunStatus::Failed, RunStatus::Unsupported}) EXPECT_EQ(parse_run_status(to_string(s)), s);
  EXPECT_FALSE(parse_run_status("OK").has_value());
}

TEST(Levels, SegmentsPerEdgeAndBack) {
  EXPECT_EQ(segments_per_edge(LevelKind::Depth, 4), 16);
  EXPECT_EQ(segments_per_edge(LevelKind::Rate, 17), 16);
  EXPECT_EQ(segments_per_edge(LevelKind::Depth, 500), -1) << "no such depth, not undefined behaviour";
  EXPECT_EQ(segments_per_edge(LevelKind::Depth, -1), -1);
  EXPECT_EQ(level_for_segments(LevelKind::Depth, 16), 4);
  EXPECT_EQ(level_for_segments(LevelKind::Rate, 16), 17);
  EXPECT_FALSE(level_for_segments(LevelKind::Depth, 12).has_value());
  EXPECT_FALSE(level_for_segments(LevelKind::Rate, 0).has_value());
}

namespace {

const std::vector<ParameterSpec> kDeclared = {
    {"fit", "samples a side", true, 65, 5, 1025, 2},
    {"scale", "a real one", false, 1.5, 0, 10, 0},
};

Parameters resolve(const std::string& text) { return Parameters::resolve(kDeclared, parse_scheme_spec(text)); }

std::string refusal(const std::string& text) {
  try {
    resolve(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Parameters, DefaultsAssignmentsAndTheCanonicalSuffix) {
  const Parameters d = resolve("geometry-image");
  EXPECT_EQ(d.integer("fit"), 65);
  EXPECT_DOUBLE_EQ(d.value("scale"), 1.5);
  EXPECT_EQ(d.suffix(), "");
  const Parameters p = resolve("geometry-image:scale=2.25,fit=129");
  EXPECT_EQ(p.integer("fit"), 129);
  EXPECT_EQ(p.suffix(), ":fit=129,scale=2.25") << "declared order, whatever the spelling's";
  EXPECT_EQ(resolve("geometry-image:fit=65").suffix(), "") << "a default spelled out names the same run";
  EXPECT_THROW(d.value("nope"), std::logic_error);
}

TEST(Parameters, BadSpellingsAreInputErrorsNamingTheSpec) {
  EXPECT_NE(refusal("g:fit=64").find("g:fit=64: parameter fit takes 5, 7, 9 ... only, not 64"), std::string::npos)
      << refusal("g:fit=64");
  EXPECT_NE(refusal("g:fit=2000").find("must lie in 5..1025"), std::string::npos);
  EXPECT_NE(refusal("g:fit=9.5").find("needs an integer"), std::string::npos);
  EXPECT_NE(refusal("g:fit=x").find("needs a number"), std::string::npos);
  EXPECT_NE(refusal("g:fit=nan").find("needs a number"), std::string::npos);
  EXPECT_NE(refusal("g:fit=1e400").find("needs a number"), std::string::npos);
  EXPECT_NE(refusal("g:size=9").find("g has no parameter 'size' (it takes fit, scale)"), std::string::npos);
  EXPECT_NE(refusal("g:fit=9,fit=11").find("given twice"), std::string::npos);
  for (const char* malformed : {"g:", "g:fit", "g:fit=", "g:=3", "g:Fit=9", "g:fit=9,", ":fit=9"})
    EXPECT_FALSE(refusal(malformed).empty()) << malformed;
}
