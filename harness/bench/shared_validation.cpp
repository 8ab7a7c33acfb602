#include "harness/bench/shared_validation.h"

#include <algorithm>
#include <cstring>

namespace sdb {
namespace {

// Plain structs without padding: their bytes are their values.
static_assert(sizeof(Point3) == 3 * sizeof(float) && sizeof(SurfaceCoord) == sizeof(uint32_t) + 2 * sizeof(float));
static_assert(sizeof(EdgeCrease) == 2 * sizeof(int) + sizeof(float) && sizeof(VertexCorner) == sizeof(int) + sizeof(float));

template <typename T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

bool same_mesh(const std::shared_ptr<const ControlMesh>& a, const std::shared_ptr<const ControlMesh>& b) {
  if (a == b) return true;
  if (!a || !b) return false;
  return same_bytes(a->positions, b->positions) && same_bytes(a->face_sizes, b->face_sizes) &&
         same_bytes(a->face_vertices, b->face_vertices) && same_bytes(a->creases, b->creases) &&
         same_bytes(a->corners, b->corners) && same_bytes(a->holes, b->holes) && a->boundary == b->boundary &&
         a->crease_method == b->crease_method && a->triangle_rule == b->triangle_rule;
}

bool same_bound(const DeviationBound& a, const DeviationBound& b) {
  return a.pos_rel_diag == b.pos_rel_diag && a.normal_deg == b.normal_deg;
}

bool same_subject(const VerdictSubject& a, const VerdictSubject& b) {
  return a.spec == b.spec && a.mesh == b.mesh && a.level == b.level && a.input == b.input && a.accepted == b.accepted &&
         same_bound(a.bound, b.bound) && same_bound(a.own_bound, b.own_bound) && a.checks == b.checks;
}

}  // namespace

bool same_output(const Tessellation& a, const Tessellation& b) {
  return same_bytes(a.positions, b.positions) && same_bytes(a.triangles, b.triangles) && same_bytes(a.normals, b.normals) &&
         same_bytes(a.coords, b.coords) && same_mesh(a.reference, b.reference);
}

void apply_verdict(RunRow& row, const Verdict& v) {
  row.watertight = v.watertight;
  row.deviation = v.deviation;
  if (v.failed) row.status = RunStatus::Failed;
  if (!v.message.empty()) row.message += (row.message.empty() ? "" : "; ") + v.message;
}

const ValidatedOutputs::Earlier* ValidatedOutputs::find(const VerdictSubject& subject, const Tessellation& output) const {
  for (const Kept& k : kept_)
    if (same_subject(k.subject, subject) && same_output(k.output, output)) return &k.earlier;
  return nullptr;
}

size_t output_bytes(const Tessellation& t) {
  return t.positions.size() * sizeof(Point3) + t.normals.size() * sizeof(Point3) + t.triangles.size() * sizeof(uint32_t) +
         t.coords.size() * sizeof(SurfaceCoord);
}

void ValidatedOutputs::remember(const VerdictSubject& subject, const Tessellation& output, std::string run, Verdict verdict) {
  kept_.erase(std::remove_if(kept_.begin(), kept_.end(),
                             [&](const Kept& k) { return k.subject.spec != subject.spec || k.subject.mesh != subject.mesh; }),
              kept_.end());
  const size_t bytes = output_bytes(output);
  if (bytes > kKeptBytes) return;  // validated on its own, as are the rows after it
  size_t kept = bytes;
  for (const Kept& k : kept_) kept += output_bytes(k.output);
  while (!kept_.empty() && kept > kKeptBytes) {
    kept -= output_bytes(kept_.front().output);
    kept_.erase(kept_.begin());
  }
  kept_.push_back({subject, output, {std::move(run), std::move(verdict)}});
}

}  // namespace sdb
