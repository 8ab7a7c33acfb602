#include "harness/results/bound_judgement.h"

#include <cmath>
#include <cstdio>
#include <vector>

namespace sdb {
namespace {

std::string figure(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

// One bound against one pair of figures; `against` names the surface they were measured from.
BoundJudgement judge_one(const DeviationBound& bound, bool measured, double position, double normal,
                         const std::string& against) {
  if (!bound_declared(bound)) return {BoundState::None, "no bound declared"};
  if (!measured) return {BoundState::Unmeasured, "deviation from " + against + " not measured"};
  std::string past;
  if (bound.pos_rel_diag >= 0 && position > bound.pos_rel_diag)
    past = "position deviation from " + against + " " + std::to_string(position) + " of the diagonal, past the bound " +
           std::to_string(bound.pos_rel_diag);
  if (bound.normal_deg >= 0 && normal > bound.normal_deg)
    past += (past.empty() ? "" : "; ") + std::string("normal deviation from ") + against + " " + std::to_string(normal) +
            " degrees, past the bound " + std::to_string(bound.normal_deg);
  if (!past.empty()) return {BoundState::Past, past};
  std::string kept = "within the bound on the deviation from " + against + " (";
  if (bound.pos_rel_diag >= 0) kept += "position " + figure(position) + " <= " + figure(bound.pos_rel_diag) + " of the diagonal";
  if (bound.normal_deg >= 0)
    kept += std::string(bound.pos_rel_diag >= 0 ? ", " : "") + "normal " + (std::isfinite(normal) ? figure(normal) : "not compared") +
            " <= " + figure(bound.normal_deg) + " deg";
  return {BoundState::Kept, kept + ")"};
}

}  // namespace

bool bound_declared(const DeviationBound& b) { return b.pos_rel_diag >= 0 || b.normal_deg >= 0; }

std::string_view to_string(BoundState s) {
  switch (s) {
    case BoundState::Kept: return "kept";
    case BoundState::Past: return "past";
    case BoundState::None: return "none";
    case BoundState::Unmeasured: return "unmeasured";
  }
  return "none";
}

BoundJudgement judge_bounds(const RunRow& row) {
  const DeviationFigures& d = row.deviation;
  std::vector<BoundJudgement> judged = {
      judge_one(row.bound, d.measured, d.pos_max_rel_diag, d.normal_max_deg, "the input's limit")};
  if (bound_declared(row.own_bound))
    judged.push_back(judge_one(row.own_bound, d.measured && d.own.has_value(), d.own ? d.own->pos_max_rel_diag : 0,
                               d.own ? d.own->normal_max_deg : 0, "the limit of its own control mesh"));
  for (const BoundState state : {BoundState::Past, BoundState::Kept, BoundState::Unmeasured}) {
    BoundJudgement out{state, ""};
    for (const BoundJudgement& j : judged)
      if (j.state == state) out.words += (out.words.empty() ? "" : "; ") + j.words;
    if (!out.words.empty()) return out;
  }
  return {BoundState::None, "no bound declared"};
}

}  // namespace sdb
