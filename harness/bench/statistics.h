// Order statistics of timing samples, the one definition every verb and paper table uses.
#pragma once

#include <vector>

namespace sdb {

// The middle value (the mean of the two middle ones for an even count); 0 for no samples.
double median(std::vector<double> samples);

}  // namespace sdb
