#include "harness/run/journal.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "harness/core/errors.h"
#include "harness/results/line_file.h"
#include "harness/results/results_check.h"
#include "harness/results/results_json.h"

namespace sdb {

using nlohmann::json;

void to_json(json& j, const RunSelection& r) {
  const Selection& s = r.selection;
  j = {{"schemes", s.schemes},     {"meshes", s.meshes},         {"backends", s.backends},
       {"levels", s.levels},       {"all", s.all_meshes},        {"all_corpus", s.all_corpus},
       {"max_triangles", s.max_triangles}, {"headline", s.headline}, {"reps", r.reps},
       {"rays", r.rays},           {"seed", r.seed},             {"validate", r.validate},
       {"quick", s.quick},         {"shard", {s.shard_index, s.shard_count}}};
}

void from_json(const json& j, RunSelection& r) {
  Selection& s = r.selection;
  j.at("schemes").get_to(s.schemes), j.at("meshes").get_to(s.meshes), j.at("backends").get_to(s.backends);
  j.at("levels").get_to(s.levels), j.at("all").get_to(s.all_meshes), j.at("all_corpus").get_to(s.all_corpus);
  j.at("max_triangles").get_to(s.max_triangles), j.at("headline").get_to(s.headline);
  j.at("reps").get_to(r.reps), j.at("rays").get_to(r.rays), j.at("seed").get_to(r.seed), j.at("validate").get_to(r.validate);
  // Journals from before the quick set and shards have neither.
  s.quick = j.value("quick", false);
  const auto shard = j.value("shard", std::vector<int>{0, 1});
  if (shard.size() != 2) throw json::other_error::create(501, "'shard' must be [index, count]", &j);
  s.shard_index = shard[0], s.shard_count = shard[1];
}

std::string selection_difference(const RunSelection& journalled, const RunSelection& now) {
  const json a = journalled, b = now;
  for (const char* key : {"schemes", "meshes", "backends", "levels", "all", "all_corpus", "reps", "rays", "seed", "validate",
                          "max_triangles", "headline", "quick", "shard"})
    if (a.at(key) != b.at(key)) return std::string(key) + ": journalled " + a.at(key).dump() + ", now " + b.at(key).dump();
  return "";
}

namespace {

std::string header_line(const JournalHeader& h) {
  json inputs = json::array();
  for (const JournalInput& in : h.inputs) inputs.push_back({{"path", in.path}, {"hash", in.hash}});
  return one_line({{"journal", kJournalVersion},
                   {"schema", kResultsSchema},
                   {"created", h.created},
                   {"cwd", h.cwd},
                   {"machine", h.machine},
                   {"selection", h.selection},
                   {"runs", h.runs},
                   {"inputs", inputs}});
}

JournalHeader parse_header(const std::string& line, const std::string& path) {
  const std::string where = at_line(path, 1);
  json j;
  try {
    j = json::parse(line);
  } catch (const json::parse_error&) {
    throw InputError(where, "not a subdivbench run journal (the header line is not JSON)");
  }
  if (!j.is_object() || !j.contains("journal")) throw InputError(where, "not a subdivbench run journal (no 'journal' version)");
  if (j["journal"] != kJournalVersion || j.value("schema", 0) != kResultsSchema)
    throw InputError(where, "journal version " + j["journal"].dump() + ", results schema " + j.value("schema", json()).dump() +
                                ": this build reads version " + std::to_string(kJournalVersion) + ", schema " +
                                std::to_string(kResultsSchema));
  JournalHeader h;
  try {
    j.at("created").get_to(h.created), j.at("cwd").get_to(h.cwd), j.at("machine").get_to(h.machine);
    j.at("selection").get_to(h.selection), j.at("runs").get_to(h.runs);
    for (const json& in : j.value("inputs", json::array()))
      h.inputs.push_back({in.at("path").get<std::string>(), in.at("hash").get<std::string>()});
  } catch (const json::exception& e) {
    throw InputError(where, std::string("corrupt journal header: ") + e.what());
  }
  return h;
}

RunRow parse_row(const std::string& line, const std::string& where) {
  RunRow row;
  try {
    row = json::parse(line).get<RunRow>();
  } catch (const json::exception& e) {
    throw InputError(where, std::string("corrupt journal row: ") + e.what());
  }
  // What results.json may not hold, the journal it is published from may not either.
  if (const std::string why = impossible_row(row); !why.empty()) throw InputError(where, "impossible journal row " + row.name() + ": " + why);
  return row;
}

}  // namespace

JournalContents read_journal(const std::string& path) {
  const LineFileContents file = read_line_file(path, "no journal here: no run to resume");
  if (file.lines.empty()) throw InputError(at_line(path, 1), "not a subdivbench run journal (no complete header line)");
  JournalContents c;
  c.header = parse_header(file.lines[0], path);
  for (size_t i = 1; i < file.lines.size(); ++i) {
    const int line = int(i) + 1;
    c.rows.push_back(parse_row(file.lines[i], at_line(path, line)));
    c.row_lines.push_back(line);
  }
  c.intact_bytes = file.intact_bytes;
  c.dropped_torn_line = file.dropped_torn_line;
  return c;
}

JournalWriter JournalWriter::create(const std::string& path, const JournalHeader& header) {
  return JournalWriter(LineFileWriter::create(path, header_line(header), "the journal"));
}

JournalWriter JournalWriter::reopen(const std::string& path, uintmax_t intact_bytes) {
  return JournalWriter(LineFileWriter::reopen(path, intact_bytes, "the journal"));
}

void JournalWriter::append(const RunRow& row) { file_.append(row_json(row, -1), "journal row " + row.name()); }

}  // namespace sdb
