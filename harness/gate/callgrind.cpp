#include "harness/gate/callgrind.h"

#include <signal.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <charconv>
#include <filesystem>
#include <fstream>

#include "harness/core/errors.h"
#include "harness/core/registry.h"
#include "harness/results/process.h"

namespace fs = std::filesystem;

namespace sdb {
namespace {

nlohmann::json read_json(const std::string& path, const char* what) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw InputError(path, std::string("is a folder, not ") + what);
  std::ifstream in(path);
  if (!in) throw InputError(path, std::string("cannot open ") + what);
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path, std::string("malformed ") + what + ": " + e.what());
  }
}

// The instruction total of a callgrind output file ("summary:" or "totals:" line).
long total_instructions(const fs::path& file, const std::string& name) {
  std::ifstream in(file);
  long total = -1;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("summary:", 0) != 0 && line.rfind("totals:", 0) != 0) continue;
    const char* begin = line.c_str() + line.find(':') + 1;
    while (*begin == ' ') ++begin;
    long value = -1;
    if (std::from_chars(begin, line.c_str() + line.size(), value).ec == std::errc()) total = value;
  }
  if (total < 0) throw InputError(name, "no instruction total in callgrind's output");
  return total;
}

// The files of one callgrind run: <out> and, with --separate-threads, <out>-01, <out>-02, ...
void remove_outputs(const fs::path& out) {
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(out.parent_path(), ec))
    if (e.path().filename().string().rfind(out.filename().string(), 0) == 0) fs::remove(e.path(), ec);
}

}  // namespace

CallgrindConfig read_callgrind_config(const std::string& path) {
  const nlohmann::json j = read_json(path, "gate configuration");
  CallgrindConfig c;
  try {
    const auto& section = j.at("callgrind");
    c.threshold = section.value("threshold", c.threshold);
    for (const auto& name : section.at("workloads").get<std::vector<std::string>>()) {
      RunSpec spec = parse_run_name(name);
      if (spec.backend != Backend::Cpu) throw InputError(path, "callgrind workloads run on cpu, not '" + name + "'");
      resolve_scheme(spec.scheme);  // an unknown scheme or parameter is named now, not in the child
      c.workloads.push_back(std::move(spec));
    }
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path, std::string("malformed callgrind section: ") + e.what());
  }
  return c;
}

std::optional<std::string> valgrind_unusable(const std::string& executable) {
  static const std::optional<std::string> why = [&]() -> std::optional<std::string> {
    ProcessResult r;
    try {
      r = run_process({"valgrind", "--tool=none", executable, "list", "backends"}, {.quiet = true});
    } catch (const std::exception& e) {
      return std::string("valgrind cannot be started: ") + e.what();
    }
    if (r.exit_code == 0) return std::nullopt;
    if (r.signal == SIGILL)
      return "valgrind cannot run " + fs::path(executable).filename().string() +
             " on this machine: it stops at an instruction a library runs while loading (SIGILL under valgrind only)";
    return "valgrind --tool=none failed (" + r.describe() + "; is valgrind installed?)";
  }();
  return why;
}

long callgrind_instructions(const RunSpec& spec, int iterations, const std::string& executable) {
  if (auto why = valgrind_unusable(executable)) throw InputError(spec.name(), *why);
  const fs::path out = fs::temp_directory_path() / ("sdb_callgrind_" + std::to_string(getpid()) + ".out");
  // The main thread's count only (--separate-threads, file -01): a cpu workload runs there, and
  // threads a scheme's prepare() left behind (TBB's workers) add a varying few hundred
  // instructions to the total (measured: +0.01% between two identical runs).
  const ProcessResult r = run_process({"valgrind", "--tool=callgrind", "--instr-atstart=no", "--separate-threads=yes",
                                       "--callgrind-out-file=" + out.string(), executable, "workload", "--scheme",
                                       spec.scheme, "--mesh", spec.mesh, "--level", std::to_string(spec.level),
                                       "--iterations", std::to_string(iterations)},
                                      {.quiet = true});
  if (r.exit_code != 0) {
    remove_outputs(out);
    throw InputError(spec.name(), "valgrind --tool=callgrind failed (" + r.describe() + "; is valgrind installed?)");
  }
  fs::path main_thread = out;
  main_thread += "-01";
  const long total = total_instructions(main_thread, spec.name());
  remove_outputs(out);
  return total;
}

std::vector<CallgrindEntry> callgrind_compare(const CallgrindConfig& config, const std::map<std::string, long>& counts,
                                              const std::map<std::string, long>& baseline) {
  std::vector<CallgrindEntry> entries;
  for (const RunSpec& w : config.workloads) {
    const std::string name = w.name();
    const auto b = baseline.find(name), c = counts.find(name);
    if (b == baseline.end() || c == counts.end() || b->second <= 0) continue;
    CallgrindEntry e{name, double(b->second), double(c->second)};
    e.change = e.current / e.baseline - 1;
    e.regression = e.change > config.threshold;
    entries.push_back(e);
  }
  return entries;
}

std::map<std::string, long> read_callgrind_counts(const std::string& path) {
  const nlohmann::json j = read_json(path, "callgrind baseline");
  try {
    return j.get<std::map<std::string, long>>();
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path, std::string("malformed callgrind baseline: ") + e.what());
  }
}

void write_callgrind_counts(const std::map<std::string, long>& counts, const std::string& path) {
  const std::string tmp = path + ".partial";
  {
    std::ofstream out(tmp);
    out << nlohmann::json(counts).dump(2) << "\n";
    if (!out) throw InputError(path, "cannot write the callgrind baseline");
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) throw InputError(path, "cannot write the callgrind baseline: " + ec.message());
}

}  // namespace sdb
