#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include "harness/gate/mann_whitney.h"

using namespace sdb;

// Our U test against scipy's mannwhitneyu (what google-benchmark's compare.py calls), on the same
// inputs: with ties, without, equal samples, and shifted ones.
TEST(MannWhitney, MatchesScipyOnTheSameInputs) {
  if (std::system("/usr/bin/python3 -c 'import scipy' 2>/dev/null") != 0) GTEST_SKIP() << "python3-scipy not installed";
  const std::vector<std::pair<std::vector<double>, std::vector<double>>> cases = {
      {{1.0, 1.1, 0.9, 1.05, 0.95, 1.02, 0.98, 1.01, 0.99}, {2.0, 2.1, 1.9, 2.05, 1.95, 2.02, 1.98, 2.01, 1.99}},
      {{1, 2, 3, 4, 5, 6, 7, 8, 9}, {1, 2, 3, 4, 5, 6, 7, 8, 9}},
      {{1, 1, 2, 2, 3, 3, 4, 4, 5}, {2, 2, 3, 3, 4, 4, 5, 5, 6}},
      {{0.5, 0.7, 0.6, 0.9, 0.8, 0.55, 0.65, 0.75, 0.85, 0.95}, {0.6, 0.8, 0.7, 1.0, 0.9, 0.65, 0.75, 0.85, 0.95}}};
  for (const auto& [a, b] : cases) {
    auto list = [](const std::vector<double>& v) {
      std::string s = "[";
      for (double x : v) s += std::to_string(x) + ",";
      return s + "]";
    };
    const std::string cmd = "/usr/bin/python3 -c 'from scipy.stats import mannwhitneyu; print(repr(mannwhitneyu(" +
                            list(a) + "," + list(b) + ", alternative=\"two-sided\").pvalue))'";
    FILE* p = popen(cmd.c_str(), "r");
    ASSERT_NE(p, nullptr);
    char buf[64] = {};
    ASSERT_NE(fgets(buf, sizeof buf, p), nullptr);
    pclose(p);
    EXPECT_NEAR(mann_whitney_p(a, b), std::stod(buf), 1e-9) << list(a) << " vs " << list(b);
  }
}
