// Two-sided Mann-Whitney U test, as google-benchmark's compare.py calls scipy's mannwhitneyu:
// the normal approximation with tie and continuity corrections (scipy's method for samples of
// 8 or more; the gate requires 9).
#pragma once

#include <vector>

namespace sdb {

double mann_whitney_p(const std::vector<double>& a, const std::vector<double>& b);

}  // namespace sdb
