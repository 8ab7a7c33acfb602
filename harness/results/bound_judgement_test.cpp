// A row's deviation against its bounds (bound_judgement.h): the one judgement measure.cpp fails
// rows by and the report prints. Hand-made rows, nothing measured.
#include "harness/results/bound_judgement.h"

#include <gtest/gtest.h>

using namespace sdb;

namespace {

RunRow measured(double position, double normal, DeviationBound bound) {
  RunRow r;
  r.bound = bound;
  r.deviation.measured = true;
  r.deviation.pos_max_rel_diag = position;
  r.deviation.normal_max_deg = normal;
  return r;
}

}  // namespace

TEST(BoundJudgement, KeptPastNoneAndUnmeasured) {
  const BoundJudgement kept = judge_bounds(measured(1e-7, 0.001, {1e-6, 0.01}));
  EXPECT_EQ(kept.state, BoundState::Kept);
  EXPECT_EQ(kept.words, "within the bound on the deviation from the input's limit (position 1e-07 <= 1e-06 of the diagonal, normal 0.001 <= 0.01 deg)");
  const BoundJudgement past = judge_bounds(measured(1e-7, 0.02, {1e-6, 0.01}));
  EXPECT_EQ(past.state, BoundState::Past);
  EXPECT_NE(past.words.find("normal deviation from the input's limit 0.020000 degrees, past the bound 0.010000"), std::string::npos)
      << past.words;
  EXPECT_EQ(past.words.find("position"), std::string::npos) << "the position kept its bound: " << past.words;
  EXPECT_EQ(judge_bounds(measured(1.0, 90, {})).state, BoundState::None);
  RunRow not_measured;
  not_measured.bound = {1e-6, 0.01};
  EXPECT_EQ(judge_bounds(not_measured).state, BoundState::Unmeasured);
}

TEST(BoundJudgement, APastOwnBoundMakesTheRowPastAndIsNamed) {
  RunRow r = measured(0.01, 1.0, {});  // the input's limit: no bound (it approximates)
  r.own_bound = {1e-6, -1};
  r.deviation.own = DeviationFigures::Own{2e-6, 1e-6, 0, 0, 0};
  const BoundJudgement j = judge_bounds(r);
  EXPECT_EQ(j.state, BoundState::Past);
  EXPECT_NE(j.words.find("the limit of its own control mesh"), std::string::npos) << j.words;
  r.deviation.own->pos_max_rel_diag = 5e-7;
  EXPECT_EQ(judge_bounds(r).state, BoundState::Kept);
  r.deviation.own.reset();
  EXPECT_EQ(judge_bounds(r).state, BoundState::Unmeasured);
}
