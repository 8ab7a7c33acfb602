// How a run ended. Names are part of the results contract ("ok", "failed", "unsupported").
#pragma once

#include <optional>
#include <string_view>

namespace sdb {

// Ok: ran and passed its checks. Failed: ran, and a check failed (an open edge or a ray crack on a
// closed input, a deviation past the scheme's bound). Unsupported: the scheme declined the request
// or the device could not hold it; the row's message says why.
enum class RunStatus { Ok, Failed, Unsupported };

std::string_view to_string(RunStatus s);
std::optional<RunStatus> parse_run_status(std::string_view s);

}  // namespace sdb
