#pragma once

#include <CLI/CLI.hpp>

namespace sdb::cli {

void register_commands(CLI::App& app);
int run_selected(const CLI::App& app);  // the chosen verb's exit code

}  // namespace sdb::cli
