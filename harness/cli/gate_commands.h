#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <map>
#include <string>

namespace sdb::cli {

// Adds bench, gate, report and the hidden workload verb (what callgrind counts).
void register_gate_commands(CLI::App& app, std::map<std::string, std::function<int()>>& verbs);

}  // namespace sdb::cli
