#include "harness/validate/watertight.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <unordered_map>

#include "harness/reference/embree_scene.h"

namespace sdb {
namespace {

struct BitsHash {
  size_t operator()(const std::array<uint32_t, 3>& k) const {
    uint64_t h = 1469598103934665603ull;
    for (uint32_t x : k) h = (h ^ x) * 1099511628211ull;
    return static_cast<size_t>(h);
  }
};

// Welds vertices with bit-identical float positions: returns the welded index of every vertex.
std::vector<uint32_t> weld(const std::vector<Point3>& positions, std::vector<Point3>* unique = nullptr) {
  std::unordered_map<std::array<uint32_t, 3>, uint32_t, BitsHash> ids;
  ids.reserve(positions.size());
  std::vector<uint32_t> remap(positions.size());
  for (size_t i = 0; i < positions.size(); ++i) {
    std::array<uint32_t, 3> key;
    std::memcpy(key.data(), positions[i].data(), sizeof key);
    auto [it, added] = ids.try_emplace(key, static_cast<uint32_t>(ids.size()));
    if (added && unique) unique->push_back(positions[i]);
    remap[i] = it->second;
  }
  return remap;
}

// splitmix64: independent, reproducible random numbers per line, whatever the thread schedule.
uint64_t mix(uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

double unit(uint64_t& state) { return (mix(state++) >> 11) * (1.0 / 9007199254740992.0); }

void random_direction(uint64_t& s, double d[3]) {
  const double z = 2 * unit(s) - 1, phi = 2 * M_PI * unit(s), r = std::sqrt(std::max(0.0, 1 - z * z));
  d[0] = r * std::cos(phi), d[1] = r * std::sin(phi), d[2] = z;
}

struct Sphere {
  double centre[3];
  double radius;
};

Sphere bounding_sphere(const std::vector<Point3>& p) {
  const Bounds b = bounds_of(p);
  return {{b.centre(0), b.centre(1), b.centre(2)}, std::max(0.5 * b.diagonal() * 1.01, 1e-6)};
}

struct BorderEdge {
  Point3 mid;
  Point3 along;  // b - a
};

// Triangle edges whose two ends lie on the same border of the same base face (u or v is 0 or 1
// at both): where cracks between patches open.
std::vector<BorderEdge> border_edges(const Tessellation& t) {
  auto on_border = [&](uint32_t a, uint32_t b) {
    const SurfaceCoord &ca = t.coords[a], &cb = t.coords[b];
    if (ca.face != cb.face) return false;
    return (ca.u == 0 && cb.u == 0) || (ca.u == 1 && cb.u == 1) || (ca.v == 0 && cb.v == 0) || (ca.v == 1 && cb.v == 1);
  };
  std::vector<BorderEdge> out;
  if (t.coords.size() != t.positions.size()) return out;
  for (size_t i = 0; i + 2 < t.triangles.size(); i += 3)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = t.triangles[i + k], b = t.triangles[i + (k + 1) % 3];
      if (a < b && on_border(a, b)) {
        const Point3 &p = t.positions[a], &q = t.positions[b];
        out.push_back({{(p[0] + q[0]) / 2, (p[1] + q[1]) / 2, (p[2] + q[2]) / 2}, {q[0] - p[0], q[1] - p[1], q[2] - p[2]}});
      }
    }
  return out;
}

constexpr float kEdgeEps = 1e-5f;

struct Line {
  double through[3], dir[3];
};

// A uniformly random line through the bounding sphere: random direction, random point of the
// sphere's disc perpendicular to it.
Line random_line(uint64_t& state, const Sphere& s) {
  Line l;
  random_direction(state, l.dir);
  double a[3];
  random_direction(state, a);
  const double dot = a[0] * l.dir[0] + a[1] * l.dir[1] + a[2] * l.dir[2];
  for (int k = 0; k < 3; ++k) a[k] -= dot * l.dir[k];
  const double len = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  const double radius = s.radius * std::sqrt(unit(state));
  for (int k = 0; k < 3; ++k) l.through[k] = s.centre[k] + radius * a[k] / len;
  return l;
}

// A line in a random direction through a point next to a random border edge: up to 2% of the
// edge's length off it (at least 0.1%, well beyond float resolution), still inside any crack
// open there.
Line border_line(uint64_t& state, const std::vector<BorderEdge>& targets) {
  Line l;
  random_direction(state, l.dir);
  const BorderEdge& e = targets[mix(state++) % targets.size()];
  double off[3];
  random_direction(state, off);
  const double len2 = double(e.along[0]) * e.along[0] + double(e.along[1]) * e.along[1] + double(e.along[2]) * e.along[2];
  const double proj = (off[0] * e.along[0] + off[1] * e.along[1] + off[2] * e.along[2]) / std::max(len2, 1e-300);
  const double scale = (0.001 + 0.019 * unit(state)) * std::sqrt(len2);
  for (int k = 0; k < 3; ++k) l.through[k] = e.mid[k] + scale * (off[k] - proj * e.along[k]);
  return l;
}

}  // namespace

long count_open_edges(const Tessellation& t) {
  const std::vector<uint32_t> id = weld(t.positions);
  std::unordered_map<uint64_t, int> uses;
  uses.reserve(t.triangles.size());
  for (size_t i = 0; i + 2 < t.triangles.size(); i += 3)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = id[t.triangles[i + k]], b = id[t.triangles[i + (k + 1) % 3]];
      if (a == b) continue;  // collapsed by welding: not an edge
      ++uses[(uint64_t(std::min(a, b)) << 32) | std::max(a, b)];
    }
  return std::count_if(uses.begin(), uses.end(), [](const auto& e) { return e.second == 1; });
}

RayCrackReport ray_crack_check(const Tessellation& t, const RayCheckOptions& options) {
  RayCrackReport report;
  report.seed = options.seed;
  if (t.triangles.empty()) return report;
  // Rays run against the welded surface, so that triangles meeting at a border share their exact
  // vertices and Embree's watertight test applies; a crack is where they do not meet.
  std::vector<Point3> unique;
  const std::vector<uint32_t> id = weld(t.positions, &unique);
  std::vector<uint32_t> tris(t.triangles.size());
  for (size_t i = 0; i < tris.size(); ++i) tris[i] = id[t.triangles[i]];
  const EmbreeTriangleScene scene(unique, tris);
  const Sphere s = bounding_sphere(unique);
  const std::vector<BorderEdge> targets = border_edges(t);
  const long border = targets.empty() ? 0 : (options.border_lines > 0 ? options.border_lines : options.random_lines);
  const long total = options.random_lines + border;

  report.rays = total;
  report.cracks = tbb::parallel_reduce(
      tbb::blocked_range<long>(0, total, 1024), 0L,
      [&](const tbb::blocked_range<long>& r, long cracks) {
        for (long i = r.begin(); i < r.end(); ++i) {
          uint64_t state = mix(options.seed * 0x100000001b3ull + static_cast<uint64_t>(i));
          // A line that passes within float resolution of an edge is undecidable (it may touch a
          // ridge, or be reported by one of two triangles): draw another. Real cracks are gaps
          // a line passes through without such a hit; narrower ones are the exact check's job.
          for (int attempt = 0; attempt < 16; ++attempt) {
            const Line line = i < options.random_lines ? random_line(state, s) : border_line(state, targets);
            float origin[3], d[3];
            for (int k = 0; k < 3; ++k)
              origin[k] = static_cast<float>(line.through[k] - 2.5 * s.radius * line.dir[k]), d[k] = static_cast<float>(line.dir[k]);
            const auto hits = scene.crossings(origin, d, static_cast<float>(5 * s.radius), kEdgeEps);
            if (hits.ambiguous) continue;
            cracks += hits.count % 2;
            break;
          }
        }
        return cracks;
      },
      std::plus<long>());
  return report;
}

}  // namespace sdb
