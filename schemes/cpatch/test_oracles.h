// Test-only stand-ins for the lead's LimitEvaluator and count_open_edges (harness/reference,
// harness/validate), used until those land on main. Small and direct on purpose: OpenSubdiv Bfr
// for the limit surface, a sort for the weld.
#pragma once

#include <opensubdiv/bfr/refinerSurfaceFactory.h>
#include <opensubdiv/bfr/surface.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <map>
#include <vector>

#include "osd_topology.h"
#include "tessellation.h"

namespace sdb::cpatch::oracle {

struct LimitPoint {
  std::array<double, 3> position{}, normal{};
};

// Catmull-Clark limit of an all-quad mesh at (face, u, v), face = ptex face.
class BfrLimit {
 public:
  explicit BfrLimit(const ControlMesh& quads)
      : refiner_(make_refiner(quads, SubdivisionRule::CatmullClark)), factory_(*refiner_, options()) {
    for (const auto& p : quads.positions) positions_.insert(positions_.end(), {double(p[0]), double(p[1]), double(p[2])});
  }
  LimitPoint at(int face, double u, double v) {
    auto& entry = surfaces_[face];
    if (entry.points.empty()) {
      factory_.InitVertexSurface(face, &entry.surface);
      entry.points.resize(3 * entry.surface.GetNumPatchPoints());
      entry.surface.PreparePatchPoints(positions_.data(), 3, entry.points.data(), 3);
    }
    const double uv[2] = {u, v};
    double p[3], du[3], dv[3];
    entry.surface.Evaluate(uv, entry.points.data(), 3, p, du, dv);
    LimitPoint out;
    out.position = {p[0], p[1], p[2]};
    const double n[3] = {du[1] * dv[2] - du[2] * dv[1], du[2] * dv[0] - du[0] * dv[2], du[0] * dv[1] - du[1] * dv[0]};
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    out.normal = {n[0] / len, n[1] / len, n[2] / len};
    return out;
  }

 private:
  static OpenSubdiv::Bfr::RefinerSurfaceFactory<>::Options options() {
    OpenSubdiv::Bfr::RefinerSurfaceFactory<>::Options o;
    o.SetApproxLevelSmooth(10);
    return o;
  }
  struct Entry {
    OpenSubdiv::Bfr::Surface<double> surface;
    std::vector<double> points;
  };
  std::unique_ptr<OpenSubdiv::Far::TopologyRefiner> refiner_;
  OpenSubdiv::Bfr::RefinerSurfaceFactory<> factory_;
  std::vector<double> positions_;
  std::map<int, Entry> surfaces_;
};

// Edges used by exactly one triangle after welding bit-identical float positions.
inline long open_edges(const Tessellation& t) {
  std::vector<std::pair<std::array<uint32_t, 3>, uint32_t>> keyed(t.positions.size());
  for (size_t i = 0; i < t.positions.size(); ++i) {
    std::array<uint32_t, 3> bits;
    std::memcpy(bits.data(), t.positions[i].data(), sizeof(bits));
    keyed[i] = {bits, static_cast<uint32_t>(i)};
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<uint32_t> weld(t.positions.size());
  uint32_t id = 0;
  for (size_t i = 0; i < keyed.size(); ++i) {
    if (i > 0 && keyed[i].first != keyed[i - 1].first) ++id;
    weld[keyed[i].second] = id;
  }
  std::vector<uint64_t> edges;
  edges.reserve(t.triangles.size());
  for (size_t f = 0; f + 2 < t.triangles.size(); f += 3)
    for (int k = 0; k < 3; ++k) {
      uint64_t a = weld[t.triangles[f + k]], b = weld[t.triangles[f + (k + 1) % 3]];
      if (a > b) std::swap(a, b);
      edges.push_back(a << 32 | b);
    }
  std::sort(edges.begin(), edges.end());
  long open = 0;
  for (size_t i = 0; i < edges.size();) {
    size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    if (j - i == 1) ++open;
    i = j;
  }
  return open;
}

}  // namespace sdb::cpatch::oracle
