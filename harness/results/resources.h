// Where the files this executable reads at run time live (reports/*.py, ci/gate.json) and which
// commit it was built from: the source tree it was built in, or, when $SUBDIVBENCH_HOME names a
// folder, that folder (a GPU bundle's top, set by the bundle's `run`: scripts/gpu-bundle), so that
// a copy of the executable on another machine never reaches for a source tree that is not there.
#pragma once

#include <string>

namespace sdb {

inline constexpr const char* kHomeVariable = "SUBDIVBENCH_HOME";
// In a bundle's top: the commit the bundle was built from, one line.
inline constexpr const char* kCommitFile = "COMMIT";

// `relative` (e.g. "reports/report.py") under $SUBDIVBENCH_HOME, else under the source tree.
std::string resource_path(const std::string& relative);

// The short commit, "-dirty" appended when tracked files were changed: from git in the source
// tree, or a bundle's COMMIT file; "" when neither says.
std::string build_commit();

}  // namespace sdb
