// Progress on a terminal (a status line rewritten in place) and elsewhere (one plain line per row),
// with an injected clock: the figures printed are the clock's, not this machine's speed.
#include <gtest/gtest.h>

#include <sstream>

#include "harness/bench/progress.h"

using namespace sdb;

namespace {

struct FakeClock {
  double now = 100;
  Progress::Clock clock() {
    return [this] { return now; };
  }
};

}  // namespace

TEST(FormatDuration, SecondsMinutesHours) {
  EXPECT_EQ(format_duration(0), "0s");
  EXPECT_EQ(format_duration(42.4), "42s");
  EXPECT_EQ(format_duration(185), "3m05s");
  EXPECT_EQ(format_duration(3720), "1h02m");
  EXPECT_EQ(format_duration(-3), "0s");
}

TEST(Progress, PlainOutputIsOneLinePerRowWithCountAndEstimate) {
  FakeClock t;
  std::ostringstream out;
  Progress p(out, false, 4, t.clock());
  p.begin("a/cpu/cube/1");
  t.now += 10;
  p.done("a/cpu/cube/1", " ok", false);
  p.begin("b/cpu/cube/1");
  t.now += 20;
  p.done("b/cpu/cube/1", " FAILED", true);
  p.close();
  EXPECT_EQ(out.str(),
            "a/cpu/cube/1 [1/4]   10s elapsed, ETA   30s ok\n"
            "b/cpu/cube/1 [2/4]   30s elapsed, ETA   30s FAILED\n");
  EXPECT_EQ(out.str().find('\r'), std::string::npos);
  EXPECT_EQ(out.str().find('\033'), std::string::npos);
}

TEST(Progress, TerminalRewritesOneStatusLineAndKeepsOnlyNotableRows) {
  FakeClock t;
  std::ostringstream out;
  {
    Progress p(out, true, 3, t.clock(), 200);
    p.begin("a/cpu/cube/1");
    t.now += 5;
    p.done("a/cpu/cube/1", " ok", false);
    p.begin("b/cpu/cube/1");
    t.now += 5;
    p.done("b/cpu/cube/1", " cracks 3", true);
  }  // the destructor clears the status line
  const std::string s = out.str();
  EXPECT_EQ(s,
            "\r\033[K[0/3]    0s elapsed, ETA    --: a/cpu/cube/1"
            "\r\033[K[1/3]    5s elapsed, ETA   10s"
            "\r\033[K[1/3]    5s elapsed, ETA   10s: b/cpu/cube/1"
            "\r\033[K"
            "b/cpu/cube/1 cracks 3\n"
            "\r\033[K[2/3]   10s elapsed, ETA    5s"
            "\r\033[K");
  EXPECT_EQ(s.find("a/cpu/cube/1 ok"), std::string::npos);  // an ok row only passes through the status line
}

TEST(Progress, TerminalStatusLineNeverWraps) {
  FakeClock t;
  std::ostringstream out;
  Progress p(out, true, 10, t.clock(), 30);
  p.begin(std::string(100, 'x'));
  const std::string s = out.str();
  const std::string line = s.substr(s.rfind("\033[K") + 3);
  EXPECT_LT(line.size(), 30u);
  EXPECT_EQ(line.substr(line.size() - 3), "...");
}

TEST(Progress, NotesInterruptTheStatusLineAndItComesBack) {
  FakeClock t;
  std::ostringstream out;
  Progress p(out, true, 2, t.clock(), 200);
  p.begin("a");
  p.note("note: skipped x");
  EXPECT_EQ(out.str(), "\r\033[K[0/2]    0s elapsed, ETA    --: a\r\033[Knote: skipped x\n\r\033[K[0/2]    0s elapsed, ETA    --: a");
}

TEST(Progress, EstimateFollowsThePaceSoFar) {
  FakeClock t;
  std::ostringstream out;
  Progress p(out, false, 10, t.clock());
  EXPECT_LT(p.eta(), 0);
  t.now += 4;
  p.done("x", "", false);
  t.now += 4;
  p.done("y", "", false);
  EXPECT_DOUBLE_EQ(p.elapsed(), 8);
  EXPECT_DOUBLE_EQ(p.eta(), 32);  // 4 s a row, 8 rows left
  EXPECT_EQ(p.finished(), 2u);
}

TEST(Progress, WithoutATotalCountsAndGivesNoEstimate) {
  FakeClock t;
  std::ostringstream out;
  Progress p(out, false, 0, t.clock());
  t.now += 3;
  p.done("cell", "", false);
  EXPECT_EQ(out.str(), "cell [1] 3s elapsed\n");
  EXPECT_LT(p.eta(), 0);
}
