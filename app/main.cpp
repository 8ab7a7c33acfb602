// subdivbench: parses the command line and calls the modules. Exit codes: 0 all ran, 1 a check
// failed (crack, deviation over bound, gate regression), 2 bad usage or bad input (one line naming
// file and line), 3 internal error.
#include <CLI/CLI.hpp>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <cstdlib>
#include <string>
#include <iostream>

#include "app/commands.h"
#include "app/main.h"
#include "harness/core/errors.h"
#include "harness/core/printable.h"

namespace sdb::app {

namespace {

// What a verb printed reached standard output, or the run says it did not: a full disk or a
// closed pipe (`info --json > /dev/full`) is an error, not exit 0 with the output lost.
int with_output_written(int code) {
  errno = 0;
  std::cout.flush();
  if (std::fflush(stdout) == 0 && !std::ferror(stdout) && std::cout.good()) return code;
  const int error = errno;
  std::cerr << "subdivbench: standard output: write failed" << (error ? std::string(": ") + std::strerror(error) : "") << "\n";
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"subdivbench: GPU subdivision methods on identical meshes, measured and validated"};
  app.require_subcommand(1);
  app.set_help_all_flag("--help-all", "Every verb's options");
  std::string device;
  app.add_option("--device", device, "Vulkan device: a substring of its name (or $SUBDIVBENCH_VK_DEVICE)");
  const Verbs verbs = register_commands(app);
  try {
    app.parse(argc, argv);
    // Device choice reads the variable wherever a Context or probe is made.
    if (!device.empty()) setenv("SUBDIVBENCH_VK_DEVICE", device.c_str(), 1);
    return with_output_written(run_selected(app, verbs));
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "subdivbench: " << printable(e.what()) << " (see --help)\n";
    return 2;
  } catch (const sdb::InputError& e) {
    std::cerr << "subdivbench: " << printable(e.what()) << "\n";
    return 2;
  } catch (const sdb::Unsupported& e) {
    // A limit the one request asked for runs into (validate, workload): bad usage, said in one line.
    std::cerr << "subdivbench: " << printable(e.what()) << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "subdivbench: internal error: " << printable(e.what()) << "\n";
    return 3;
  }
}

}  // namespace sdb::app
