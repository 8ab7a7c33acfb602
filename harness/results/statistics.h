// Order statistics of timing samples, the one definition every verb and paper table uses.
#pragma once

#include <vector>

namespace sdb {

// The middle value (the mean of the two middle ones for an even count); 0 for no samples.
double median(std::vector<double> samples);

// How far apart two sizes (triangle counts) are in ratio, |ln(a / b)|, each taken as at least 1:
// what "the level nearest N triangles" means wherever a level is chosen by size.
double log_distance(double a, double b);

}  // namespace sdb
