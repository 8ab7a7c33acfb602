// A row's deviation against the bounds it declares, judged once, here: measure.cpp fails a row
// past them, and the report says of every row which bound it kept or passed (reports/overview.cpp
// hands these words to the script, which judges nothing).
#pragma once

#include <string>
#include <string_view>

#include "harness/results/results.h"

namespace sdb {

enum class BoundState { Kept, Past, None, Unmeasured };
std::string_view to_string(BoundState s);  // "kept" | "past" | "none" | "unmeasured"

struct BoundJudgement {
  BoundState state = BoundState::None;
  std::string words;  // "within the bound (position 1.2e-07 <= 1e-06 of the diagonal)", "position deviation ... past the bound ..."
};

// Whether a scheme declares the bound (either figure; -1 each where it declares none).
bool bound_declared(const DeviationBound& bound);

// The row's deviation from the input's limit against RunRow::bound and, where the scheme declares
// one, its distance from its own control mesh's limit (deviation.own) against RunRow::own_bound.
// Past where either is past; else kept where one is kept; else unmeasured where a bound is
// declared but its figure was not measured; else none.
BoundJudgement judge_bounds(const RunRow& row);

}  // namespace sdb
