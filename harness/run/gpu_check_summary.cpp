#include "harness/run/gpu_check_summary.h"

#include <cstdio>
#include <map>

namespace sdb {
namespace {

std::string format(const char* fmt, auto... args) {
  char buf[512];
  std::snprintf(buf, sizeof buf, fmt, args...);
  return buf;
}

std::string clipped(std::string s, size_t width) {
  if (s.size() > width) s = s.substr(0, width - 3) + "...";
  return s;
}

std::string device_lines_vulkan(const MachineInfo& m) {
  if (m.vulkan_device.empty()) return "Vulkan: no device";
  std::string line = "Vulkan: " + m.vulkan_device;
  if (on_cpu_implementation(m, Backend::Vulkan)) line += ": a CPU implementation of Vulkan (lavapipe), NOT a GPU";
  else line += " (" + (m.vulkan_device_type.empty() ? std::string("?") : m.vulkan_device_type) + " GPU)";
  return line;
}

// The paired ratio of `row` to the CPU row beside it, "12.34x cpu-mt" (its own) or "3.10x osd-bfr".
std::string against_cpu(const std::vector<PairedCell>& cells, const std::string& mesh, const RunRow& row) {
  for (const PairedCell& c : cells) {
    if (c.mesh != mesh || c.row.scheme != row.spelled() || c.row.backend != row.backend || c.row.level != row.level) continue;
    if (is_gpu(c.peer.backend)) continue;
    const std::string other = c.peer.scheme == c.row.scheme ? std::string(to_string(c.peer.backend)) : c.peer.scheme;
    return format("%.2fx %s", c.rate_ratio_median, other.c_str());
  }
  return "-";
}

std::string mesh_base(const std::string& mesh) {
  const size_t slash = mesh.rfind('/');
  return slash == std::string::npos ? mesh : mesh.substr(slash + 1);
}

std::string level_text(const RunRow& r) {
  // Rate schemes count N x N samples; depth schemes 2^k segments: the row's tessellation says which.
  return r.tessellation == r.level - 1 ? "N=" + std::to_string(r.level) : "d=" + std::to_string(r.level);
}

std::string stages_line(const ResultsFile& results, const CheckProgress& p) {
  std::string line = "gpu-check " + results.created + ", commit " + (results.machine.git_commit.empty() ? "?" : results.machine.git_commit) +
                     ": " + std::to_string(p.ok) + " of " + std::to_string(p.stages) + " stages ok";
  if (p.failed) line += ", " + std::to_string(p.failed) + " failed";
  if (p.cut_off) line += ", " + std::to_string(p.cut_off) + " cut off";
  if (p.not_run) line += ", " + std::to_string(p.not_run) + " not run";
  return line;
}

}  // namespace

std::vector<std::string> gpu_check_summary(const ResultsFile& results, const CheckProgress& p) {
  const MachineInfo& m = results.machine;
  std::vector<std::string> lines = {stages_line(results, p), clipped(device_lines_vulkan(m), 100)};
  if (!m.vulkan_device.empty()) {
    lines.push_back(clipped("  driver " + m.vulkan_driver + ", Vulkan " + m.vulkan_api, 100));
    lines.push_back(format("  write bandwidth: buffer fill %.1f GB/s, store-only shader %.1f GB/s; device memory %.1f GiB",
                           m.gpu_write_bandwidth_gbs, m.gpu_shader_write_bandwidth_gbs, m.vulkan_memory_gib));
  }
  if (!m.opengl_renderer.empty())
    lines.push_back(clipped("OpenGL: " + m.opengl_renderer +
                                (on_cpu_implementation(m, Backend::OpenGl) ? ": a CPU implementation of OpenGL, NOT a GPU" : ""),
                            100));
  lines.push_back(clipped(format("CPU: %s, %d cores, write bandwidth %.1f GB/s (all threads)", m.cpu_model.c_str(), m.cores,
                                 m.write_bandwidth_mt_gbs),
                          100));

  // The best GPU row of each scheme, in the order the rows came (the registry's).
  std::vector<std::string> order;
  std::map<std::string, const RunRow*> best;
  for (const RunRow& r : results.runs) {
    if (!is_gpu(r.backend) || r.status != RunStatus::Ok) continue;
    const RunRow*& b = best[r.spelled()];
    if (!b) order.push_back(r.spelled());
    if (!b || r.triangle_rate_mtris > b->triangle_rate_mtris) b = &r;
  }
  lines.push_back("best rate per scheme, evaluate-only (bw: of the fill bandwidth; against CPU: paired rate ratio):");
  lines.push_back(format("%-22s %-7s %-19s %-4s %5s %8s %4s %s", "scheme", "backend", "mesh", "lvl", "Mtris", "Mtris/s",
                         "bw", "against CPU"));
  const RunRow* fastest = nullptr;
  bool any_cpu_implementation = false;
  for (const std::string& spec : order) {
    const RunRow& r = *best[spec];
    const bool cpu_impl = on_cpu_implementation(m, r.backend);
    any_cpu_implementation |= cpu_impl;
    if (!cpu_impl && (!fastest || r.triangle_rate_mtris > fastest->triangle_rate_mtris)) fastest = &r;
    lines.push_back(clipped(format("%-22s %-7s %-19s %-4s %5.1f %8.1f %4.2f %s", clipped(spec, 22).c_str(),
                                   (std::string(to_string(r.backend)) + (cpu_impl ? "*" : "")).c_str(),
                                   clipped(mesh_base(r.mesh), 19).c_str(), level_text(r).c_str(), r.triangles / 1e6,
                                   r.triangle_rate_mtris, r.bandwidth_fraction, against_cpu(results.paired, r.mesh, r).c_str()),
                            100));
  }
  if (order.empty()) lines.push_back("  (no GPU row has been measured yet)");
  if (any_cpu_implementation)
    lines.push_back("* on a CPU implementation (lavapipe, llvmpipe): checks the device path, not a GPU figure; not ranked");
  if (fastest) {
    const bool in_range = fastest->triangles >= 10'000'000 && fastest->triangles <= 100'000'000;
    const char* verdict = !in_range ? "not judged (outside 10-100 M triangles)"
                          : fastest->triangle_rate_mtris >= kGpuRateTargetMtris ? "met" : "NOT met";
    lines.push_back(clipped(format("GPU target >= %.0f G triangles/s: %s; fastest: %s (%s), %.2f G/s at %.1f M",
                                   kGpuRateTargetMtris / 1e3, verdict, fastest->spelled().c_str(),
                                   std::string(to_string(fastest->backend)).c_str(), fastest->triangle_rate_mtris / 1e3,
                                   fastest->triangles / 1e6),
                            100));
  } else if (!order.empty()) {
    lines.push_back("no GPU here: nothing is ranked");
  }
  for (const std::string& n : p.notes) lines.push_back(clipped("note: " + n, 100));
  for (size_t i = 0; i < p.problems.size() && i < 2; ++i) lines.push_back(clipped("problem: " + p.problems[i], 100));
  if (p.problems.size() > 2) lines.push_back("problem: " + std::to_string(p.problems.size() - 2) + " more (gpu-check.jsonl)");
  if (p.not_run || p.cut_off)
    lines.push_back(format("the budget (%.0f s) ended the check: `gpu-check --resume` measures what is missing", p.budget_s));
  if (p.report == "pending") lines.push_back("report: written at the end");
  else lines.push_back(p.report.empty() ? "report: report.html, report.md" : clipped("report: not written: " + p.report, 100));
  return lines;
}

}  // namespace sdb
