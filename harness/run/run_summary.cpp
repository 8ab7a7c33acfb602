#include "harness/run/run_summary.h"

#include <cstdio>
#include <filesystem>
#include <map>
#include <set>

#include "harness/bench/paired.h"

namespace sdb {

bool has_crack(const RunRow& r) {
  const bool closed_checked = r.watertight.ray_cracks >= 0;
  return closed_checked && (r.watertight.open_edges > 0 || r.watertight.ray_cracks > 0);
}

RunSummary summarise(const std::vector<RunRow>& rows) {
  RunSummary s;
  for (const RunRow& r : rows) {
    if (r.status == RunStatus::Ok) ++s.ok;
    else if (r.status == RunStatus::Unsupported) ++s.unsupported;
    else ++s.failed;
    if (has_crack(r)) {
      s.not_watertight.push_back(r.name() + ": " + std::to_string(r.watertight.open_edges) + " open edges, " +
                                 std::to_string(r.watertight.ray_cracks) + " ray cracks of " +
                                 std::to_string(r.watertight.rays) + " rays");
    } else if (r.status == RunStatus::Failed) {
      s.failures.push_back(r.name() + ": " + r.message);
    }
  }
  return s;
}

std::vector<std::string> summary_lines(const RunSummary& s, const std::string& results_json, const std::string& report_dir) {
  std::vector<std::string> lines;
  lines.push_back(std::to_string(s.ok + s.unsupported + s.failed) + " rows: " + std::to_string(s.ok) + " ok, " +
                  std::to_string(s.unsupported) + " unsupported, " + std::to_string(s.failed) + " failed");
  if (s.not_watertight.empty()) {
    lines.push_back("watertight: every closed input gave a closed surface without ray cracks");
  } else {
    lines.push_back("NOT watertight (" + std::to_string(s.not_watertight.size()) + " rows):");
    for (const std::string& n : s.not_watertight) lines.push_back("  " + n);
  }
  if (!s.failures.empty()) {
    lines.push_back("other failures (" + std::to_string(s.failures.size()) + " rows):");
    for (const std::string& f : s.failures) lines.push_back("  " + f);
  }
  lines.push_back("wrote " + results_json);
  if (!report_dir.empty()) {
    const std::filesystem::path dir(report_dir);
    lines.push_back("wrote " + (dir / "report.html").string() + " (and " + (dir / "report.md").string() + ")");
  }
  return lines;
}

namespace {

double rate_mtris(const PairedSide& side, double time_ms) { return time_ms > 0 ? double(side.triangles) / (time_ms * 1e3) : 0; }

// The fastest side among the cells' on one mesh and backend, and its own cell (its ratio to its
// peer), null for a scheme without a peer.
std::pair<PairedSide, const PairedCell*> fastest(const std::vector<PairedCell>& cells, const std::string& mesh, Backend backend,
                                                 double& rate) {
  PairedSide best;
  rate = -1;
  for (const PairedCell& c : cells) {
    if (c.mesh != mesh) continue;
    if (c.row.backend == backend && rate_mtris(c.row, c.time_ms_median) > rate) best = c.row, rate = rate_mtris(c.row, c.time_ms_median);
    if (c.peer.backend == backend && rate_mtris(c.peer, c.peer_time_ms_median) > rate)
      best = c.peer, rate = rate_mtris(c.peer, c.peer_time_ms_median);
  }
  for (const PairedCell& c : cells)
    if (c.mesh == mesh && c.row.backend == backend && c.row.scheme == best.scheme && !is_backend_cell(c)) return {best, &c};
  return {best, nullptr};
}

// A backend's name, marked where its rows ran on a CPU implementation of the API.
std::string backend_text(Backend b, const MachineInfo* machine) {
  return std::string(to_string(b)) + (machine && on_cpu_implementation(*machine, b) ? "*" : "");
}

// The backend cells (paired.h) as lines: a GPU row's rate over its own scheme's cpu-mt rate.
std::vector<std::string> backend_lines(const std::vector<PairedCell>& cells, const MachineInfo* machine) {
  std::vector<std::string> lines;
  for (const PairedCell& c : cells) {
    if (!is_backend_cell(c)) continue;
    if (lines.empty()) lines.push_back("GPU against the same scheme's CPU (paired rounds: median rate ratio, range over rounds):");
    char buf[320];
    std::snprintf(buf, sizeof buf, "  %-28s %-24s %-7s %.3fx %s (%.3f-%.3f over %d rounds; %.3f against %.3f ms)", c.mesh.c_str(),
                  c.row.scheme.c_str(), backend_text(c.row.backend, machine).c_str(), c.rate_ratio_median,
                  std::string(to_string(c.peer.backend)).c_str(), c.rate_ratio_min, c.rate_ratio_max, c.rounds,
                  c.time_ms_median, c.peer_time_ms_median);
    lines.push_back(buf);
  }
  return lines;
}

}  // namespace

std::vector<std::string> paired_lines(const std::vector<PairedCell>& cells, const MachineInfo* machine) {
  std::vector<std::string> lines;
  if (cells.empty()) return lines;
  std::map<std::string, std::set<Backend>> backends;
  for (const PairedCell& c : cells) backends[c.mesh].insert({c.row.backend, c.peer.backend});
  lines.push_back("fastest per mesh and backend (paired rounds: median ratio to the peer, range over rounds):");
  for (const auto& [mesh, used] : backends)
    for (Backend backend : used) {
      double rate = 0;
      const auto [side, own] = fastest(cells, mesh, backend, rate);
      char buf[256];
      std::snprintf(buf, sizeof buf, "  %-28s %-7s %-24s %9.2f Mtri/s", mesh.c_str(), backend_text(backend, machine).c_str(),
                    side.scheme.c_str(), rate);
      std::string line = buf;
      if (own) {
        std::snprintf(buf, sizeof buf, "  %.2fx %s/%s (%.2f-%.2f over %d rounds)", own->rate_ratio_median, own->peer.scheme.c_str(),
                      std::string(to_string(own->peer.backend)).c_str(), own->rate_ratio_min, own->rate_ratio_max, own->rounds);
        line += buf;
      } else {
        line += "  (no peer of its own in this run)";
      }
      lines.push_back(line);
    }
  for (std::string& line : backend_lines(cells, machine)) lines.push_back(std::move(line));
  std::set<Backend> used;
  for (const PairedCell& c : cells) used.insert({c.row.backend, c.peer.backend});
  for (Backend b : used)
    if (machine && on_cpu_implementation(*machine, b))
      lines.push_back("* " + std::string(to_string(b)) + ": " + cpu_implementation_words(*machine, b) +
                      ": its rates check the device path, they are not GPU figures");
  return lines;
}

}  // namespace sdb
