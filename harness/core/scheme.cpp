#include "harness/core/scheme.h"

#include <algorithm>
#include <limits>

namespace sdb {

std::string_view to_string(SchemeRole role) {
  switch (role) {
    case SchemeRole::Peer: return "peer";
    case SchemeRole::Method: return "method";
    case SchemeRole::Test: return "test";
  }
  return "?";
}

std::string_view to_string(LimitClaim claim) {
  return claim == LimitClaim::Approximates ? "approximates" : "reproduces";
}

int segments_per_edge(LevelKind kind, int level) {
  if (kind == LevelKind::Rate) return level - 1;
  return level >= 0 && level < 31 ? 1 << level : -1;  // -1: no such depth
}

std::optional<int> level_for_segments(LevelKind kind, int segments) {
  if (segments < 1) return std::nullopt;
  if (kind == LevelKind::Rate) return segments + 1;
  for (int k = 0; k < 31; ++k)
    if ((1 << k) == segments) return k;
  return std::nullopt;
}

RunRequest default_request(const SchemeInfo& info, Backend backend, int level, int threads) {
  return {backend, level, threads, Parameters::defaults(info.parameters)};
}

namespace {

// The largest sharpness below OpenSubdiv's infinite one (Sdc::Crease::SHARPNESS_INFINITE, 10) of
// the mesh's creases and corners: what still decays at the next levels; 0 without any.
double largest_finite_sharpness(const ControlMesh& mesh) {
  constexpr double kInfinite = 10.0;
  double largest = 0;
  for (const EdgeCrease& c : mesh.creases)
    if (c.sharpness < kInfinite) largest = std::max(largest, double(c.sharpness));
  for (const VertexCorner& c : mesh.corners)
    if (c.sharpness < kInfinite) largest = std::max(largest, double(c.sharpness));
  return largest;
}

}  // namespace

bool reproduces_limit(const SchemeInfo& info, const RunRequest& request, const ControlMesh& mesh) {
  if (info.limit == LimitClaim::Approximates) return false;
  const std::string& projection = info.limit_projection_parameter;
  if (!projection.empty() && request.parameters.values().count(projection) && request.parameters.integer(projection) == 0)
    return false;
  if (info.limit == LimitClaim::ReproducesOnceSharpnessDecays)
    return info.level_kind == LevelKind::Depth && request.level >= largest_finite_sharpness(mesh);
  return true;
}

long Scheme::estimated_triangles(const ControlMesh& accepted, const RunRequest& request) const {
  const SchemeInfo& i = info();
  const long seg = segments_per_edge(i.level_kind, request.level);
  long doubled = 0;  // twice the count, to keep it integral
  for (int n : accepted.face_sizes) doubled += n == 4 ? 4 : (n == 3 && i.reference == SubdivisionRule::Loop ? 2 : n);
  const double triangles = double(doubled) * double(seg) * double(seg) / 2;  // saturates instead of wrapping
  return triangles > 9e18 ? std::numeric_limits<long>::max() : static_cast<long>(triangles);
}

double Scheme::estimated_peak_bytes(const ControlMesh& accepted, const RunRequest& request) const {
  return double(estimated_triangles(accepted, request)) * info().peak_bytes_per_triangle;
}

}  // namespace sdb
