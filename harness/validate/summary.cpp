#include "harness/validate/summary.h"

#include <algorithm>
#include <cmath>

namespace sdb {

std::vector<char> referenced(const Tessellation& t) {
  std::vector<char> used(t.positions.size(), 0);
  for (uint32_t i : t.triangles) used[i] = 1;
  return used;
}

Stats stats_of(std::vector<double> v) {
  Stats s;
  if (v.empty()) return s;
  double sum = 0, sq = 0;
  for (double x : v) sum += x, sq += x * x, s.max = std::max(s.max, x);
  s.mean = sum / v.size();
  s.rms = std::sqrt(sq / v.size());
  const size_t k = static_cast<size_t>(std::ceil(0.95 * v.size())) - 1;
  std::nth_element(v.begin(), v.begin() + static_cast<long>(k), v.end());
  s.p95 = v[k];
  return s;
}

}  // namespace sdb
