// The verbs of subdivbench. Each add_*_verbs adds its subcommands to `app` and their actions to
// `verbs` by name; options live in state the actions capture, not in globals.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <map>
#include <string>

namespace sdb::app {

using Verbs = std::map<std::string, std::function<int()>>;

// Caps on counts a user gives: each is work proportional to it (or memory: Google Benchmark keeps
// every repetition), and past these a run takes hours or ends in bad_alloc rather than answering.
// Rays: 10 M lines (and as many aimed at borders) take minutes on two cores already.
inline constexpr long kMaxRays = 10'000'000;
inline constexpr int kMaxReps = 1000, kMaxRounds = 1000;

Verbs register_commands(CLI::App& app);
int run_selected(const CLI::App& app, const Verbs& verbs);  // the chosen verb's exit code

// list, info (commands.cpp); validate, run (run_commands.cpp); bench, gate, report, paper and the
// hidden workload (gate_commands.cpp); pictures (picture_commands.cpp); gpu-check (gpu_check_commands.cpp).
void add_mesh_verbs(CLI::App& app, Verbs& verbs);
void add_run_verbs(CLI::App& app, Verbs& verbs);
void add_gate_verbs(CLI::App& app, Verbs& verbs);
void add_picture_verbs(CLI::App& app, Verbs& verbs);
void add_gpu_check_verbs(CLI::App& app, Verbs& verbs);

}  // namespace sdb::app
