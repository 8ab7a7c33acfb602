#include "harness/run/row_lines.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "harness/core/printable.h"

namespace sdb {

std::string row_head(const RunRow& r) {
  std::string head = printable(r.name());
  head.resize(std::max<size_t>(head.size(), 44), ' ');
  return head;
}

std::string row_figures(const RunRow& r) {
  char buf[512];
  std::string line;
  if (r.status == RunStatus::Unsupported) return " unsupported: " + printable(r.message);
  std::snprintf(buf, sizeof buf, " %9ld tris %9.3f ms %8.2f Mtri/s bw %5.1f%%", r.triangles,
                r.gpu_time_ms ? r.gpu_time_ms->median : r.time_ms.median, r.triangle_rate_mtris, 100 * r.bandwidth_fraction);
  line += buf;
  if (r.watertight.open_edges >= 0) line += "  open " + std::to_string(r.watertight.open_edges);
  if (r.watertight.ray_cracks >= 0)
    line += " cracks " + std::to_string(r.watertight.ray_cracks) + "/" + std::to_string(r.watertight.rays);
  if (r.deviation.measured) {
    std::snprintf(buf, sizeof buf, "  dev max %.3g%% p95 %.3g%%", r.deviation.pos_max_pct, r.deviation.pos_p95_pct);
    line += buf;
    // NaN: no normal compared (a scheme that outputs none, mipgh-quadtri's nodes).
    if (std::isnan(r.deviation.normal_max_deg)) {
      line += " no normals";
    } else {
      std::snprintf(buf, sizeof buf, " %.3gdeg", r.deviation.normal_max_deg);
      line += buf;
    }
    if (r.limit == "approximates") {
      std::snprintf(buf, sizeof buf, "  approximates%s: max %.2g p95 %.2g of the diagonal",
                    r.deviation.measured_by == "nearest-point" ? " (nearest points)" : "", r.deviation.pos_max_rel_diag,
                    r.deviation.pos_p95_rel_diag);
      line += buf;
    }
  }
  if (r.status != RunStatus::Ok) line += "  FAILED: " + printable(r.message);
  else if (!r.message.empty()) line += "  (" + printable(r.message) + ")";
  return line;
}

void print_row(const RunRow& r) { std::printf("%s%s\n", row_head(r).c_str(), row_figures(r).c_str()); }

}  // namespace sdb
