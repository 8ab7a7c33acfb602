#include "harness/run/run_set.h"

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <deque>
#include <filesystem>
#include <set>

#include "harness/bench/machine.h"
#include "harness/run/row_worker.h"
#include "harness/core/content_hash.h"
#include "harness/core/errors.h"
#include "harness/results/output_folder.h"
#include "harness/results/process.h"

namespace fs = std::filesystem;

namespace sdb {

namespace {

std::vector<std::string> run_names(const Plan& plan) {
  std::vector<std::string> names;
  for (const RunSpec& r : plan.runs) names.push_back(r.name());
  return names;
}

std::string plan_difference(const std::vector<std::string>& journalled, const std::vector<std::string>& now) {
  for (size_t i = 0; i < std::max(journalled.size(), now.size()); ++i) {
    const std::string a = i < journalled.size() ? journalled[i] : "(none)", b = i < now.size() ? now[i] : "(none)";
    if (a != b)
      return "this selection now plans " + std::to_string(now.size()) + " runs, the journal " + std::to_string(journalled.size()) +
             "; run " + std::to_string(i + 1) + " was " + a + ", now " + b + " (a backend or the corpus changed?)";
  }
  return "";
}

// Nothing ran (every row unsupported): said, exit 2, and no earlier results replaced.
void require_something_ran(const ResultsFile& results) {
  for (const RunRow& r : results.runs)
    if (r.status != RunStatus::Unsupported) return;
  throw InputError("run", "nothing ran: all " + std::to_string(results.runs.size()) + " runs unsupported (" +
                              (results.runs.empty() ? std::string() : results.runs.front().message) +
                              "); results.json and the report left as they were");
}

// The files the plan's meshes were read from (given by path, or found in the corpus), each with
// the hash of its content now; generated meshes have none.
std::vector<JournalInput> input_files(const Plan& plan, MeasureContext& context) {
  std::set<std::string> meshes;
  for (const RunSpec& r : plan.runs) meshes.insert(r.mesh);
  std::vector<JournalInput> inputs;
  for (const std::string& name : meshes) {
    const std::string& source = context.mesh(name).source;
    std::error_code ec;
    if (source.rfind("builtin:", 0) == 0 || !fs::is_regular_file(source, ec)) continue;
    const auto hash = file_content_hash(source);
    if (!hash) throw InputError(source, "cannot read it to record its content in the journal");
    inputs.push_back({source, hex64(*hash)});
  }
  return inputs;
}

// A journalled input whose content is not what it was: its journalled rows measured another file.
void refuse_changed_inputs(const std::vector<JournalInput>& journalled, const std::vector<JournalInput>& now,
                           const std::string& journal) {
  for (const JournalInput& was : journalled) {
    const auto it = std::find_if(now.begin(), now.end(), [&](const JournalInput& n) { return n.path == was.path; });
    const std::string hash = it == now.end() ? "unreadable" : it->hash;
    if (hash != was.hash)
      throw InputError(was.path, "changed since " + journal + " recorded it (content hash " + was.hash + ", now " + hash +
                                     "): its journalled rows measured the old file; start a new run");
  }
}

// A journal that holds fewer rows than its run planned is a run someone may want to resume; a new
// run replaces it only when told to (--force), and says so.
void keep_unfinished_journal(const std::string& path, bool force) {
  std::error_code ec;
  if (!fs::exists(path, ec)) return;
  JournalContents old;
  try {
    old = read_journal(path);
  } catch (const InputError& e) {
    std::printf("note: replacing a journal this build cannot resume (%s)\n", e.what());
    return;
  }
  if (old.rows.size() >= old.header.runs.size()) return;
  const std::string what = "holds an unfinished run (" + std::to_string(old.rows.size()) + " of " +
                           std::to_string(old.header.runs.size()) + " rows, started " + old.header.created + ")";
  if (!force)
    throw InputError(path, what + ": continue it with `run --resume " + fs::path(path).parent_path().string() +
                               "`, or replace it with --force");
  std::printf("note: %s %s; replaced (--force)\n", path.c_str(), what.c_str());
}

}  // namespace

RunSet::RunSet(std::string out, const MachineInfo& machine, bool isolate)
    : out_(std::move(out)), isolate_(isolate), context_(std::make_unique<MeasureContext>(machine)) {}
RunSet::RunSet(RunSet&&) noexcept = default;
RunSet::~RunSet() = default;

const MachineInfo& RunSet::machine() const { return context_->machine(); }
std::string RunSet::journal_path() const { return (fs::path(out_) / kJournalFile).string(); }

RunSet RunSet::start(const std::string& out, const RunSelection& selection, bool isolate, bool force) {
  prepare_output_folder(out);  // before the measuring, not after it
  FolderLock lock = FolderLock::take(out);
  RunSet set(out, describe_machine_or_reuse(), isolate);
  set.lock_ = std::make_unique<FolderLock>(std::move(lock));
  set.selection_ = selection;
  // A bad selection (no such scheme, mesh or run) is said at once, not after seconds of probes.
  set.plan_ = make_plan(selection.selection, *set.context_);
  if (set.plan_.runs.empty()) return set;
  keep_unfinished_journal(set.journal_path(), force);
  const std::vector<JournalInput> inputs = input_files(set.plan_, *set.context_);
  set.context_->probe_bandwidth();
  const JournalHeader header{set.machine(), utc_now(), fs::current_path().string(), selection, run_names(set.plan_), inputs};
  set.journal_.emplace(JournalWriter::create(set.journal_path(), header));
  return set;
}

RunSet RunSet::resume(const std::string& out, const std::optional<RunSelection>& selection, bool isolate) {
  const std::string path = (fs::path(out) / kJournalFile).string();
  std::error_code ec;
  std::optional<FolderLock> lock;
  if (fs::is_directory(out, ec)) lock.emplace(FolderLock::take(out));
  JournalContents journal = read_journal(path);
  const JournalHeader& h = journal.header;
  if (selection && !(*selection == h.selection))
    throw InputError(path, "the interrupted run had another selection (" + selection_difference(h.selection, *selection) +
                               "): resume with its options or none");
  // The rows already journalled must be comparable with the ones still to measure.
  const MachineInfo here = describe_machine_or_reuse();
  if (here.git_commit != h.machine.git_commit)
    throw InputError(path, "journalled at commit " + h.machine.git_commit + ", this build is " + here.git_commit +
                               ": resume with the build that started the run");
  if (const std::string d = machine_difference(h.machine, here); !d.empty())
    throw InputError(path, "journalled on another machine (" + d + ")");
  if (fs::current_path().string() != h.cwd)
    throw InputError(path, "journalled in " + h.cwd + " (mesh paths are relative to it): resume from there");
  // The journal's machine block, probes included: every row reads its bandwidth against the same.
  RunSet set(out, h.machine, isolate);
  if (lock) set.lock_ = std::make_unique<FolderLock>(std::move(*lock));
  set.selection_ = h.selection;
  set.plan_ = make_plan(h.selection.selection, *set.context_);
  if (const std::string d = plan_difference(h.runs, run_names(set.plan_)); !d.empty()) throw InputError(path, d);
  refuse_changed_inputs(h.inputs, input_files(set.plan_, *set.context_), path);
  std::map<std::string, int> planned;
  for (const std::string& name : h.runs) ++planned[name];
  for (size_t i = 0; i < journal.rows.size(); ++i) {
    const std::string name = journal.rows[i].name();
    if (++set.done_[name] > planned[name])
      throw InputError(at_line(path, journal.row_lines[i]), "row " + name + (planned[name] ? " journalled twice" : " is not in the run's plan"));
  }
  set.journalled_ = journal.rows.size();
  set.dropped_torn_line_ = journal.dropped_torn_line;
  set.journal_.emplace(JournalWriter::reopen(path, journal.intact_bytes));
  return set;
}

void RunSet::measure_remaining(const std::function<void(const RunRow&)>& on_row, const std::function<void(const RunSpec&)>& on_start) {
  const MeasureOptions options = measure_options(selection_);
  std::optional<RowWorker> worker;
  if (isolate_) worker.emplace(self_executable(), machine(), options);
  std::map<std::string, int> skip = done_;
  for (const RunSpec& spec : plan_.runs) {
    if (skip[spec.name()]-- > 0) continue;
    if (on_start) on_start(spec);
    const RunRow row = worker ? worker->measure(spec) : measure_run(spec, options, *context_);
    journal_->append(row);
    ++done_[spec.name()];
    on_row(row);
  }
}

ResultsFile RunSet::results() const {
  const JournalContents journal = read_journal(journal_path());
  std::map<std::string, std::deque<RunRow>> by_name;
  for (const RunRow& r : journal.rows) by_name[r.name()].push_back(r);
  ResultsFile results;
  results.machine = journal.header.machine;
  results.created = journal.header.created;
  for (const RunSpec& spec : plan_.runs) {
    auto& rows = by_name[spec.name()];
    if (rows.empty()) throw std::logic_error("publish: " + spec.name() + " is not journalled");
    results.runs.push_back(std::move(rows.front()));
    rows.pop_front();
  }
  const Selection& sel = selection_.selection;
  if (sel.shard_count > 1) results.shard = ShardInfo{sel.shard_index, sel.shard_count};
  return results;
}

void RunSet::publish(const ResultsFile& results, const ReportWriter& report) const {
  require_something_ran(results);
  publish_results(results, out_, report);
}

void publish_results(const ResultsFile& results, const std::string& dir, const RunSet::ReportWriter& report) {
  const fs::path staging = fs::path(dir) / ".publishing";
  std::error_code ec;
  fs::remove_all(staging, ec);  // what a killed publish left
  fs::create_directories(staging, ec);
  if (ec) throw InputError(staging.string(), "cannot make a staging folder: " + ec.message());
  try {
    write_results(results, (staging / "results.json").string());
    if (report) report((staging / "results.json").string(), staging.string());
  } catch (const std::exception& e) {
    fs::remove_all(staging, ec);
    throw InputError(dir, std::string("nothing replaced: ") + e.what() + " (the rows are in " + kJournalFile +
                              "; `run --resume " + dir + "` publishes them again)");
  }
  // Every file is written: now they replace the earlier set, results.json first; the folders
  // (plots, pictures) file by file, so that files of the user's beside ours stay.
  try {
    fs::rename(staging / "results.json", fs::path(dir) / "results.json", ec);
    if (ec) throw InputError((fs::path(dir) / "results.json").string(), "cannot write results (is it a folder?)");
    merge_into_folder(staging, dir, false);
  } catch (const InputError&) {
    fs::remove_all(staging, ec);
    throw;
  }
  fs::remove_all(staging, ec);
}

}  // namespace sdb
