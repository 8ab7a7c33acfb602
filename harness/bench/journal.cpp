#include "harness/bench/journal.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "harness/bench/results_check.h"
#include "harness/bench/results_json.h"
#include "harness/core/errors.h"

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
                   {"inputs", inputs}}) +
         "\n";
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

std::string read_whole(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(path, "no journal here: no run to resume");
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path, "not a regular file");
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in) throw InputError(path, "cannot read the journal");
  return text.str();
}

// Writes all of `data` or says why not.
std::string write_all(int fd, const std::string& data) {
  for (size_t done = 0; done < data.size();) {
    const ssize_t n = write(fd, data.data() + done, data.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return std::strerror(errno);
    done += size_t(n);
  }
  return fsync(fd) == 0 ? "" : std::strerror(errno);
}

void sync_folder_of(const std::string& path) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  const int dir = open(parent.empty() ? "." : parent.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir < 0) return;
  fsync(dir);  // the rename itself survives a power cut
  close(dir);
}

}  // namespace

JournalContents read_journal(const std::string& path) {
  const std::string text = read_whole(path);
  JournalContents c;
  size_t start = 0;
  for (int line = 1;; ++line) {
    const size_t nl = text.find('\n', start);
    if (nl == std::string::npos) {
      // What follows the last newline was cut off mid-write: the row it held was not journalled.
      if (line == 1) throw InputError(at_line(path, 1), "not a subdivbench run journal (no complete header line)");
      c.dropped_torn_line = start < text.size();
      break;
    }
    const std::string content = text.substr(start, nl - start);
    if (line == 1) {
      c.header = parse_header(content, path);
    } else {
      c.rows.push_back(parse_row(content, at_line(path, line)));
      c.row_lines.push_back(line);
    }
    start = nl + 1;
    c.intact_bytes = start;
  }
  return c;
}

JournalWriter::JournalWriter(std::string path, int fd) : path_(std::move(path)), fd_(fd) {}
JournalWriter::JournalWriter(JournalWriter&& other) noexcept : path_(std::move(other.path_)), fd_(other.fd_) { other.fd_ = -1; }
JournalWriter::~JournalWriter() {
  if (fd_ >= 0) close(fd_);
}

JournalWriter JournalWriter::create(const std::string& path, const JournalHeader& header) {
  const std::string tmp = path + ".partial";
  const int fd = open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw InputError(path, std::string("cannot start the journal: ") + std::strerror(errno));
  const std::string failed = write_all(fd, header_line(header));
  close(fd);
  std::error_code ec;
  if (!failed.empty()) {
    std::filesystem::remove(tmp, ec);
    throw InputError(path, "cannot start the journal: " + failed);
  }
  // Renamed into place whole: a journal always starts with a complete header.
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw InputError(path, "cannot start the journal (is it a folder?)");
  }
  sync_folder_of(path);
  return reopen(path, std::filesystem::file_size(path));
}

JournalWriter JournalWriter::reopen(const std::string& path, uintmax_t intact_bytes) {
  const int fd = open(path.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
  if (fd < 0) throw InputError(path, std::string("cannot open the journal: ") + std::strerror(errno));
  if (ftruncate(fd, off_t(intact_bytes)) != 0) {
    const std::string why = std::strerror(errno);
    close(fd);
    throw InputError(path, "cannot drop the journal's torn last line: " + why);
  }
  return JournalWriter(path, fd);
}

void JournalWriter::append(const RunRow& row) {
  struct stat before {};
  fstat(fd_, &before);
  const std::string failed = write_all(fd_, row_json(row, -1) + "\n");
  if (failed.empty()) return;
  // A line cut short (a full disk) would read as torn and be dropped; cut it now, so that the
  // journal stays whole for --resume whatever happens next.
  if (ftruncate(fd_, before.st_size) == 0) fsync(fd_);
  throw InputError(path_, "cannot journal row " + row.name() + ": " + failed);
}

}  // namespace sdb
