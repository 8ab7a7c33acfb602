// How far two backends' outputs of one request lie apart, node for node: what the Vulkan tests
// of every scheme assert against the cpu's.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

#include <functional>
#include <string>
#include <vector>

#include "harness/core/control_mesh.h"
#include "harness/core/scheme.h"
#include "harness/core/tessellation.h"

namespace sdb::conformance {

struct Agreement {
  double max_rel = 0, max_deg = 0;  // largest position gap over `diagonal`; largest normal angle
  size_t identical = 0, vertices = 0;  // positions bit-identical, of all
};

// `a` and `b` lay their output out the same (the caller checks the counts).
inline Agreement agreement(const Tessellation& a, const Tessellation& b, double diagonal) {
  Agreement r;
  r.vertices = a.positions.size();
  for (size_t i = 0; i < a.positions.size(); ++i) {
    const Point3 &p = a.positions[i], &q = b.positions[i];
    r.identical += p == q;
    const double dx = double(p[0]) - q[0], dy = double(p[1]) - q[1], dz = double(p[2]) - q[2];
    r.max_rel = std::max(r.max_rel, std::sqrt(dx * dx + dy * dy + dz * dz) / diagonal);
    if (i >= a.normals.size() || i >= b.normals.size()) continue;
    const Point3 &m = a.normals[i], &n = b.normals[i];
    const double c[3] = {double(m[1]) * n[2] - double(m[2]) * n[1], double(m[2]) * n[0] - double(m[0]) * n[2],
                         double(m[0]) * n[1] - double(m[1]) * n[0]};
    const double dot = double(m[0]) * n[0] + double(m[1]) * n[1] + double(m[2]) * n[2];
    r.max_deg = std::max(r.max_deg, std::atan2(std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]), dot) * 180 / M_PI);
  }
  return r;
}

// What a scheme's Vulkan test asks of the device's output against the cpu's.
struct VulkanExpectations {
  double max_rel = 1e-6;  // of the diagonal
  double max_deg = 1e-3;  // between normals
  long open_edges = -1;   // on the vulkan output; -1: as many as the cpu's
  long rays = 0;          // ray-crack check on a closed input without holes (0: none)
};

// One request on `backend` (the scheme's evaluation, executed); throws Unsupported where the
// device refuses it.
using BackendRun = std::function<Tessellation(Backend backend)>;

// Runs cpu and vulkan, and EXPECTs (GoogleTest) the same layout, agreement within `e`, the open
// edges and no ray crack. A request the device refuses is said on stdout and gives an empty
// Agreement (vertices 0).
Agreement expect_vulkan_agrees(const std::string& name, int depth, const ControlMesh& accepted, const BackendRun& run,
                               const VulkanExpectations& e);

// The corpus sweep of a Vulkan test: every sweep shape of `rule` accepted as `scheme` takes it and
// taken by `cpu_prepare` (which throws InputError where the cpu refuses it), depths 1..5 while the
// output stays under 20,000 triangles (depth 1 always), each through `check`; prints the totals.
// Skips the test where there is no shared corpus.
using SweepCheck = std::function<Agreement(const std::string& name, const ControlMesh& accepted, int depth)>;
void vulkan_sweep(SubdivisionRule rule, const std::string& scheme,
                  const std::function<void(const ControlMesh&)>& cpu_prepare, const SweepCheck& check);

// Runs `e` once and EXPECTs its GPU passes' labels to be `expected`, in order, and its kernel time
// their sum (upload and readback apart); skips where the queue has no timestamps.
void expect_passes_timed(Evaluation& e, const std::vector<std::string>& expected);

}  // namespace sdb::conformance
