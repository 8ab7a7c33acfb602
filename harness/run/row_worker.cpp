#include "harness/run/row_worker.h"

#include <sys/prctl.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <optional>

#include "harness/core/errors.h"
#include "harness/results/process.h"
#include "harness/results/results_json.h"

namespace sdb {

using nlohmann::json;

namespace {

constexpr int kChannelFd = 3;

json options_json(const MeasureOptions& o) {
  return {{"reps", o.reps},         {"min_time_s", o.min_time_s}, {"time", o.time},
          {"validate", o.validate}, {"hausdorff", o.hausdorff},   {"rays", o.rays},
          {"seed", o.seed},         {"threads", o.threads},       {"deviation_ply", o.deviation_ply},
          {"refusals_as_rows", o.refusals_as_rows}, {"hausdorff_only_without_coords", o.hausdorff_only_without_coords},
          {"unjudged_deviation", o.unjudged_deviation}};
}

MeasureOptions options_from(const json& j) {
  MeasureOptions o;
  j.at("reps").get_to(o.reps), j.at("min_time_s").get_to(o.min_time_s), j.at("time").get_to(o.time);
  j.at("validate").get_to(o.validate), j.at("hausdorff").get_to(o.hausdorff), j.at("rays").get_to(o.rays);
  j.at("seed").get_to(o.seed), j.at("threads").get_to(o.threads), j.at("deviation_ply").get_to(o.deviation_ply);
  j.at("refusals_as_rows").get_to(o.refusals_as_rows);
  j.at("hausdorff_only_without_coords").get_to(o.hausdorff_only_without_coords);
  j.at("unjudged_deviation").get_to(o.unjudged_deviation);
  return o;
}

}  // namespace

std::string options_line(const MeasureOptions& o) { return one_line(options_json(o)); }
MeasureOptions options_from_line(const std::string& line) { return options_from(json::parse(line)); }

namespace {

json run_json(const RunSpec& spec) {
  return {{"scheme", spec.scheme}, {"mesh", spec.mesh}, {"backend", to_string(spec.backend)}, {"level", spec.level}};
}

RunSpec run_from(const json& r) {
  const auto backend = parse_backend(r.at("backend").get<std::string>());
  if (!backend) throw std::runtime_error("row worker: unknown backend in the job");
  return {r.at("scheme").get<std::string>(), r.at("mesh").get<std::string>(), *backend, r.at("level").get<int>()};
}

// What the worker said about the row in hand.
struct WorkerReport {
  std::string stage = "start";  // before its first report: reading and accepting the mesh
  std::optional<RunRow> row;    // the row as it stood at the last stage, or the finished row
  bool finished = false;
  std::string error_kind, error;  // "input" | "unsupported" | "internal"
  bool done() const { return finished || !error_kind.empty(); }
};

void take_line(WorkerReport& report, const std::string& line) {
  const json j = json::parse(line);
  if (j.contains("stage")) report.stage = j["stage"].get<std::string>();
  if (j.contains("row")) report.row = j["row"].get<RunRow>();
  if (j.contains("finished")) report.finished = true;
  if (j.contains("error")) report.error_kind = j["error"].get<std::string>(), report.error = j.at("message").get<std::string>();
}

[[noreturn]] void end_as_interrupted(int signal) {
  std::signal(signal, SIG_DFL);
  std::raise(signal);
  std::_Exit(128 + signal);
}

void send(int fd, const json& j) {
  const std::string line = one_line(j) + "\n";
  for (size_t done = 0; done < line.size();) {
    const ssize_t n = write(fd, line.data() + done, line.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) std::_Exit(4);  // the parent is gone: nobody to measure for
    done += size_t(n);
  }
}

// One job: its stages, then the row or the error, on `fd`.
void serve_row(const json& job, std::unique_ptr<MeasureContext>& context, int fd) {
  try {
    if (!context) context = std::make_unique<MeasureContext>(job.at("machine").get<MachineInfo>());
    MeasureOptions options = options_from(job.at("options"));
    options.on_stage = [fd](const char* stage, const RunRow& row) { send(fd, {{"stage", stage}, {"row", row}}); };
    send(fd, {{"finished", true}, {"row", measure_run(run_from(job.at("run")), options, *context)}});
  } catch (const InputError& e) {
    send(fd, {{"error", "input"}, {"message", e.what()}});
  } catch (const Unsupported& e) {
    send(fd, {{"error", "unsupported"}, {"message", e.what()}});
  } catch (const std::exception& e) {
    send(fd, {{"error", "internal"}, {"message", e.what()}});
  }
}

}  // namespace

RowWorker::RowWorker(std::string executable, MachineInfo machine, MeasureOptions options)
    : executable_(std::move(executable)), machine_(std::move(machine)), options_(std::move(options)) {}
RowWorker::~RowWorker() = default;

RunRow RowWorker::measure(const RunSpec& spec) {
  const std::string job = one_line({{"run", run_json(spec)}, {"options", options_json(options_)}, {"machine", machine_}});
  if (!process_ || !process_->send_line(job)) {
    process_ = std::make_unique<ChannelProcess>(
        std::vector<std::string>{executable_, "row-worker", "--channel-fd", std::to_string(kChannelFd), "--parent",
                                 std::to_string(getpid())},
        kChannelFd);
    if (!process_->send_line(job)) throw std::runtime_error("the row worker ended before its first job");
  }
  WorkerReport report;
  while (!report.done())
    if (auto line = process_->read_line()) take_line(report, *line);
    else break;
  if (report.finished && report.row) return *report.row;
  if (report.error_kind == "input") throw InputError("", report.error);
  if (report.error_kind == "unsupported") throw Unsupported(report.error);
  if (report.error_kind == "internal") throw std::runtime_error(report.error);
  // The channel closed mid-row: the worker is dead.
  const ProcessResult ended = process_->wait();
  process_.reset();
  if (ended.signal == SIGINT || ended.signal == SIGTERM || ended.signal == SIGHUP) end_as_interrupted(ended.signal);
  RunRow row = report.row ? *report.row : describe_spec(spec, machine_);
  row.status = RunStatus::Failed;
  const std::string what = ended.signal ? "crashed during " : "worker exited during ";
  row.message = what + report.stage + ": " + ended.describe() + (row.message.empty() ? "" : "; " + row.message);
  return row;
}

void serve_rows(int fd, long parent) {
  // Dies with the parent (a kill -9 of `run` must not leave a worker measuring), and not at all
  // if the parent is already gone.
  prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (getppid() != parent) std::_Exit(4);
  std::unique_ptr<MeasureContext> context;
  std::string pending;
  char buf[65536];
  for (;;) {
    const ssize_t n = read(fd, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // the parent closed the channel: the run is over
    pending.append(buf, size_t(n));
    for (size_t nl; (nl = pending.find('\n')) != std::string::npos;) {
      serve_row(json::parse(pending.substr(0, nl)), context, fd);
      pending.erase(0, nl + 1);
    }
  }
  std::fflush(stdout);
  std::fflush(stderr);
  std::_Exit(0);
}

}  // namespace sdb
