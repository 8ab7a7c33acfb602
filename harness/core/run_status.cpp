#include "harness/core/run_status.h"

namespace sdb {

std::string_view to_string(RunStatus s) {
  switch (s) {
    case RunStatus::Ok: return "ok";
    case RunStatus::Failed: return "failed";
    case RunStatus::Unsupported: return "unsupported";
  }
  return "?";
}

std::optional<RunStatus> parse_run_status(std::string_view s) {
  for (RunStatus r : {RunStatus::Ok, RunStatus::Failed, RunStatus::Unsupported})
    if (s == to_string(r)) return r;
  return std::nullopt;
}

}  // namespace sdb
