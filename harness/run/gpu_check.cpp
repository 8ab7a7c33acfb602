#include "harness/run/gpu_check.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <set>

#include "harness/run/gpu_check_plan.h"
#include "harness/run/gpu_check_summary.h"
#include "harness/bench/machine.h"
#include "harness/core/errors.h"
#include "harness/core/registry.h"
#include "harness/gl/context.h"
#include "harness/gpu/device_info.h"
#include "harness/results/line_file.h"
#include "harness/results/process.h"
#include "harness/results/results_json.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace sdb {
namespace {

constexpr int kJournalVersion = 1;
constexpr const char* kDeviceStage = "device";
constexpr const char* kDeviceFile = "device.json";  // the machine block with its probes, no rows
// The render-mode paper tables: frames of conversion, evaluation and rasterization on the device.
const char* const kRenderTables[] = {"ni2008-table4", "shiue-loop-table1"};

enum class StageKind { Device, Group, Paper };

struct Stage {
  StageKind kind;
  std::string name;  // in the journal
  std::string slug;  // its folder and log
  const CheckGroup* group = nullptr;
  std::string table;  // paper table id
};

struct Outcome {
  std::string status;  // "ok", "failed", "cut off"
  std::string message;
  double seconds = 0;
};

using Clock = std::chrono::steady_clock;

std::string seconds_text(double s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f s", s);
  return buf;
}

std::vector<Stage> stages_of(const CheckPlan& plan) {
  std::vector<Stage> stages = {{StageKind::Device, kDeviceStage, kDeviceStage}};
  for (const CheckGroup& g : plan.groups) stages.push_back({StageKind::Group, g.name(), g.slug(), &g});
  std::set<std::string> registered;
  for (const PaperTable& t : paper_tables()) registered.insert(t.id);
  for (const char* id : kRenderTables)
    if (registered.count(id)) stages.push_back({StageKind::Paper, std::string("paper ") + id, std::string("paper-") + id, nullptr, id});
  return stages;
}

std::vector<std::string> stage_names(const std::vector<Stage>& stages) {
  std::vector<std::string> names;
  for (const Stage& s : stages) names.push_back(s.name);
  return names;
}

json header_json(const MachineInfo& machine, const GpuCheckOptions& o, int rounds, const std::vector<Stage>& stages) {
  return {{"gpu_check", kJournalVersion}, {"created", utc_now()},   {"machine", machine},
          {"quick", o.quick},             {"rounds", rounds},        {"stages", stage_names(stages)}};
}

// The stages already journalled (the last word on each); InputError when the journal is not this
// check's: another commit, machine, quick flag, rounds or plan.
std::map<std::string, Outcome> resume_journal(const std::string& path, const json& now, LineFileContents& file) {
  file = read_line_file(path, "no gpu-check journal here: nothing to resume");
  if (file.lines.empty()) throw InputError(at_line(path, 1), "not a gpu-check journal (no complete header line)");
  json h;
  try {
    h = json::parse(file.lines[0]);
  } catch (const json::parse_error&) {
    throw InputError(at_line(path, 1), "not a gpu-check journal (the header line is not JSON)");
  }
  if (!h.is_object() || h.value("gpu_check", 0) != kJournalVersion)
    throw InputError(at_line(path, 1), "not a gpu-check journal of version " + std::to_string(kJournalVersion));
  MachineInfo then, here = now.at("machine").get<MachineInfo>();
  try {
    then = h.at("machine").get<MachineInfo>();
  } catch (const json::exception& e) {
    throw InputError(at_line(path, 1), std::string("corrupt gpu-check journal header: ") + e.what());
  }
  if (then.git_commit != here.git_commit)
    throw InputError(path, "journalled at commit " + then.git_commit + ", this build is " + here.git_commit +
                               ": resume with the build that started the check");
  if (const std::string d = machine_difference(then, here); !d.empty()) throw InputError(path, "journalled on another machine (" + d + ")");
  for (const char* key : {"quick", "rounds", "stages"})
    if (h.value(key, json()) != now.at(key))
      throw InputError(path, std::string("the journalled check had other ") + key + " (" + h.value(key, json()).dump() +
                                 ", now " + now.at(key).dump() + "): start it again without --resume");
  std::map<std::string, Outcome> done;
  for (size_t i = 1; i < file.lines.size(); ++i) {
    try {
      const json j = json::parse(file.lines[i]);
      done[j.at("stage").get<std::string>()] = {j.at("status"), j.value("message", ""), j.value("seconds", 0.0)};
    } catch (const json::exception& e) {
      throw InputError(at_line(path, int(i) + 1), std::string("corrupt gpu-check journal line: ") + e.what());
    }
  }
  return done;
}

// The last non-empty line of a log, for a one-line reason.
std::string last_line(const fs::path& log) {
  std::ifstream in(log);
  std::string line, last;
  while (std::getline(in, line))
    if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
  return last;
}

class GpuCheck {
 public:
  GpuCheck(const GpuCheckOptions& o, const CheckReportWriter& report, MeasureContext& context, CheckPlan plan)
      : o_(o), report_(report), out_(o.out), context_(context), plan_(std::move(plan)), stages_(stages_of(plan_)) {
    rounds_ = o.rounds > 0 ? o.rounds : o.quick ? 1 : 3;
    progress_.stages = stages_.size();
    progress_.notes = plan_.notes;
    progress_.budget_s = o.budget_s;
  }

  // The stages with their runs, nothing measured or written.
  int print_plan() const {
    for (const std::string& n : plan_.notes) std::printf("gpu-check: %s\n", n.c_str());
    for (size_t i = 0; i < stages_.size(); ++i) {
      const Stage& s = stages_[i];
      std::printf("[%zu/%zu] %s%s\n", i + 1, stages_.size(), s.name.c_str(), s.group ? describe(*s.group).c_str() : "");
      if (s.group)
        for (const RunSpec& r : s.group->runs) std::printf("      %s\n", r.name().c_str());
    }
    std::printf("gpu-check: %zu stages, %d paired rounds each, a budget of %.0f s\n", stages_.size(), rounds_, o_.budget_s);
    return 0;
  }

  int run() {
    if (o_.plan_only) return print_plan();
    const fs::path journal_path = out_ / kGpuCheckJournal;
    const json header = header_json(context_.machine(), o_, rounds_, stages_);
    if (o_.resume) {
      LineFileContents file;
      done_ = resume_journal(journal_path.string(), header, file);
      journal_.emplace(LineFileWriter::reopen(journal_path.string(), file.intact_bytes, "the gpu-check journal"));
      std::printf("gpu-check: resuming %s: %zu of %zu stages journalled\n", out_.c_str(), done_.size(), stages_.size());
    } else {
      journal_.emplace(LineFileWriter::create(journal_path.string(), one_line(header), "the gpu-check journal"));
    }
    for (const std::string& n : plan_.notes) std::printf("gpu-check: %s\n", n.c_str());
    fs::create_directories(out_ / "stages");
    fs::create_directories(out_ / "logs");
    for (size_t i = 0; i < stages_.size(); ++i) run_stage(i);
    return finish();
  }

 private:
  double elapsed() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

  void run_stage(size_t i) {
    const Stage& s = stages_[i];
    std::printf("[%zu/%zu] %s%s", i + 1, stages_.size(), s.name.c_str(), s.group ? describe(*s.group).c_str() : "");
    auto it = done_.find(s.name);
    const bool device_file_missing = s.kind == StageKind::Device && !fs::exists(out_ / kDeviceFile);
    if (it != done_.end() && it->second.status != "cut off" && !device_file_missing) {
      std::printf(": journalled (%s)\n", it->second.status.c_str());
      count(s, it->second);
      return;
    }
    // The device facts always: every later stage reads its rows against their probes.
    const double left = o_.budget_s - elapsed();
    if (left < 1 && s.kind != StageKind::Device) {
      std::printf(": not run (the budget of %.0f s is spent)\n", o_.budget_s);
      ++progress_.not_run;
      return;
    }
    std::printf("\n");
    std::fflush(stdout);
    const auto started = Clock::now();
    Outcome outcome = s.kind == StageKind::Device ? device_stage() : child_stage(s, left);
    outcome.seconds = std::chrono::duration<double>(Clock::now() - started).count();
    json line = {{"stage", s.name}, {"status", outcome.status}, {"seconds", outcome.seconds}, {"message", outcome.message}};
    journal_->append(one_line(line), "journal stage " + s.name);
    done_[s.name] = outcome;
    std::printf("      %s in %s%s%s\n", outcome.status.c_str(), seconds_text(outcome.seconds).c_str(),
                outcome.message.empty() ? "" : ": ", outcome.message.c_str());
    count(s, outcome);
    publish_so_far("pending");
  }

  std::string describe(const CheckGroup& g) const {
    const Scheme* s = find_scheme(g.scheme);
    const bool depth = s && s->info().level_kind == LevelKind::Depth;
    char buf[200];
    std::snprintf(buf, sizeof buf, " (%s, %s %d, %.2f M triangles)", g.mesh.c_str(), depth ? "depth" : "N =", g.level,
                  g.triangles / 1e6);
    return buf;
  }

  void count(const Stage& s, const Outcome& outcome) {
    if (outcome.status == "ok") ++progress_.ok;
    else {
      (outcome.status == "cut off" ? progress_.cut_off : progress_.failed) += 1;
      progress_.problems.push_back(s.name + ": " + outcome.status + (outcome.message.empty() ? "" : ": " + outcome.message));
    }
  }

  // Device facts and the write-bandwidth probes, measured here once; every bench child reads its
  // rows' bandwidth fractions against them (bench --machine-from).
  Outcome device_stage() {
    MachineInfo m = context_.machine();
    add_bandwidth_probes(m);
    ResultsFile device;
    device.machine = m;
    device.created = utc_now();
    write_results(device, (out_ / kDeviceFile).string());
    const gpu::DeviceInfo vk = gpu::probe();
    std::printf("      Vulkan: %s%s\n", gpu::summary(vk).c_str(),
                on_cpu_implementation(m, Backend::Vulkan) ? " (a CPU implementation of Vulkan, not a GPU)" : "");
    std::printf("      device-local memory %.1f GiB; write bandwidth: buffer fill %.2f GB/s, store-only shader %.2f GB/s\n",
                m.vulkan_memory_gib, m.gpu_write_bandwidth_gbs, m.gpu_shader_write_bandwidth_gbs);
    if (!m.opengl_renderer.empty())
      std::printf("      OpenGL: %s%s\n", m.opengl_renderer.c_str(),
                  on_cpu_implementation(m, Backend::OpenGl) ? " (a CPU implementation of OpenGL, not a GPU)" : "");
    std::printf("      CPU: %s, %d cores, write bandwidth %.2f GB/s (one thread), %.2f GB/s (all)\n", m.cpu_model.c_str(),
                m.cores, m.write_bandwidth_gbs, m.write_bandwidth_mt_gbs);
    return {"ok", "", 0};
  }

  std::vector<std::string> child_argv(const Stage& s) const {
    std::vector<std::string> argv = {self_executable()};
    if (s.kind == StageKind::Paper) {
      argv.insert(argv.end(), {"paper", s.table, "--out", (out_ / "paper").string()});
      if (o_.quick) argv.push_back("--quick");
      return argv;
    }
    argv.insert(argv.end(), {"bench", "--machine-from", (out_ / kDeviceFile).string(), "--rounds", std::to_string(rounds_),
                             "--out", (out_ / "stages" / s.slug).string(),
                             std::string("--benchmark_min_time=") + (o_.quick ? "0.02" : "0.1")});
    for (const RunSpec& r : s.group->runs) argv.insert(argv.end(), {"--run", r.name()});
    return argv;
  }

  fs::path product(const Stage& s) const {
    return s.kind == StageKind::Paper ? out_ / "paper" / (s.table + ".md") : out_ / "stages" / s.slug / "results.json";
  }

  Outcome child_stage(const Stage& s, double left_s) {
    const fs::path log = out_ / "logs" / (s.slug + ".log");
    std::error_code ec;
    fs::remove(log, ec);
    fs::remove(product(s), ec);  // a cut-off stage's earlier product is not this run's
    ProcessOptions options;
    options.output_file = log.string();
    options.timeout_s = left_s;
    const ProcessResult r = run_process(child_argv(s), options);
    if (r.timed_out) return {"cut off", "stopped when the budget of " + seconds_text(o_.budget_s) + " was spent", 0};
    if (r.exit_code == 0 && fs::exists(product(s))) return {"ok", s.group ? group_figures(s) : "", 0};
    std::string why = r.describe();
    if (const std::string last = last_line(log); !last.empty()) why += ": " + last;
    return {"failed", why + " (" + fs::relative(log, out_).string() + ")", 0};
  }

  // "vulkan 2345.6 M tris/s (bw 0.41), cpu-mt 45.6 M tris/s" from a group's results.
  std::string group_figures(const Stage& s) const {
    std::string words;
    for (const RunRow& r : read_results(product(s).string()).runs) {
      if (r.scheme == kCalibrationScheme) continue;
      const std::string who = (r.scheme == s.group->scheme ? "" : r.scheme + " ") + std::string(to_string(r.backend));
      char buf[160];
      std::snprintf(buf, sizeof buf, "%s %.1f M tris/s (bw %.2f)", who.c_str(), r.triangle_rate_mtris, r.bandwidth_fraction);
      words += (words.empty() ? "" : ", ") + std::string(buf);
    }
    return words;
  }

  // The rows and paired cells of every finished group (calibration rows, the gate's unit, left
  // out; a CPU row two groups share kept once), with the device stage's machine.
  ResultsFile merged() const {
    ResultsFile results;
    if (fs::exists(out_ / kDeviceFile)) results.machine = read_results((out_ / kDeviceFile).string()).machine;
    else results.machine = context_.machine();
    results.created = utc_now();
    results.rounds = rounds_;
    std::set<std::string> seen;
    for (const Stage& s : stages_) {
      if (s.kind != StageKind::Group || !is_ok(s)) continue;
      const ResultsFile part = read_results(product(s).string());
      for (const RunRow& r : part.runs)
        if (r.scheme != kCalibrationScheme && seen.insert(r.name()).second) results.runs.push_back(r);
      results.paired.insert(results.paired.end(), part.paired.begin(), part.paired.end());
    }
    return results;
  }

  bool is_ok(const Stage& s) const {
    const auto it = done_.find(s.name);
    return it != done_.end() && it->second.status == "ok" && fs::exists(product(s));
  }

  std::vector<std::string> publish_so_far(const std::string& report) {
    const ResultsFile results = merged();
    write_results(results, (out_ / "results.json").string());
    progress_.report = report;
    const std::vector<std::string> lines = gpu_check_summary(results, progress_);
    const fs::path tmp = out_ / (std::string(kGpuCheckSummary) + ".partial");
    {
      std::ofstream f(tmp);
      for (const std::string& l : lines) f << l << "\n";
      if (!f) throw InputError(tmp.string(), "cannot write the summary");
    }
    fs::rename(tmp, out_ / kGpuCheckSummary);
    return lines;
  }

  int finish() {
    std::vector<std::string> papers;
    for (const Stage& s : stages_)
      if (s.kind == StageKind::Paper && fs::exists(product(s)) && done_.count(s.name)) papers.push_back(product(s).string());
    std::string report;
    try {
      publish_so_far("pending");
      report_((out_ / "results.json").string(), out_.string(), papers);
    } catch (const std::exception& e) {
      report = e.what();
    }
    const std::vector<std::string> lines = publish_so_far(report);
    std::printf("\n");
    for (const std::string& l : lines) std::printf("%s\n", l.c_str());
    std::printf("gpu-check: results.json, summary.txt%s in %s\n", report.empty() ? ", report and paper tables" : "",
                out_.c_str());
    const bool complete = progress_.ok == stages_.size();
    return complete && report.empty() ? 0 : 1;
  }

  const GpuCheckOptions& o_;
  const CheckReportWriter& report_;
  fs::path out_;
  MeasureContext& context_;
  CheckPlan plan_;
  std::vector<Stage> stages_;
  int rounds_ = 1;
  CheckProgress progress_;
  std::map<std::string, Outcome> done_;
  std::optional<LineFileWriter> journal_;
  Clock::time_point start_ = Clock::now();
};

std::vector<Backend> usable_gpu_backends() {
  std::vector<Backend> b = {Backend::Vulkan};
  if (gl::probe().available) b.push_back(Backend::OpenGl);
  return b;
}

}  // namespace

int run_gpu_check(const GpuCheckOptions& o, const CheckReportWriter& report) {
  // A check that cannot be resumed is said at once, whatever the device.
  if (o.resume) read_line_file((fs::path(o.out) / kGpuCheckJournal).string(), "no gpu-check journal here: nothing to resume");
  const gpu::DeviceInfo vk = gpu::probe();
  if (!vk.available) {
    std::printf("gpu-check: no Vulkan device here (%s); nothing to check\n", vk.reason.c_str());
    return 0;
  }
  if (vk.type == gpu::DeviceType::Cpu && !o.allow_cpu_device) {
    std::printf("gpu-check: the only Vulkan device is a CPU implementation (%s); no GPU to check "
                "(--allow-cpu-device runs it anyway)\n",
                gpu::summary(vk).c_str());
    return 0;
  }
  if (!o.plan_only) prepare_output_folder(o.out);
  std::printf("gpu-check: %s%s\n", gpu::summary(vk).c_str(),
              vk.type == gpu::DeviceType::Cpu ? " (a CPU implementation of Vulkan: its rates are not GPU figures)" : "");
  std::fflush(stdout);
  MeasureContext context(describe_machine());
  CheckPlan plan = plan_gpu_check(o.quick ? kGpuCheckQuickBounds : kGpuCheckBounds, o.quick, usable_gpu_backends(), context);
  return GpuCheck(o, report, context, std::move(plan)).run();
}

}  // namespace sdb
