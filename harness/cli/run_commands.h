#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <map>
#include <string>

namespace sdb::cli {

// Adds validate, run and bench; each verb's action goes into `verbs` by name.
void register_run_commands(CLI::App& app, std::map<std::string, std::function<int()>>& verbs);

}  // namespace sdb::cli
