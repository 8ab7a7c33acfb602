#include "embree_scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace sdb {
namespace {

// Embree reports through a C callback; exceptions must not cross it, so keep the message and
// let check_device() throw on the C++ side.
thread_local std::string g_embree_error;

void embree_error(void*, RTCError code, const char* message) {
  if (g_embree_error.empty())
    g_embree_error = "Embree error " + std::to_string(code) + ": " + (message ? message : "");
}

void check_device(const char* what) {
  if (g_embree_error.empty()) return;
  const std::string msg = std::string(what) + ": " + g_embree_error;
  g_embree_error.clear();
  throw std::runtime_error(msg);
}

// An intersect context that carries the hit list: the filter rejects every hit so traversal
// continues and records it, giving all crossings of the ray.
struct Hit {
  float t;
  uint32_t prim;
  bool entering;  // dir . geometric normal < 0
};

struct AllHitsContext {
  RTCIntersectContext base;
  std::vector<Hit>* hits;
};

void record_hit(const RTCFilterFunctionNArguments* args) {
  auto* ctx = reinterpret_cast<AllHitsContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (!args->valid[i]) continue;
    const float facing = RTCRayN_dir_x(args->ray, args->N, i) * RTCHitN_Ng_x(args->hit, args->N, i) +
                         RTCRayN_dir_y(args->ray, args->N, i) * RTCHitN_Ng_y(args->hit, args->N, i) +
                         RTCRayN_dir_z(args->ray, args->N, i) * RTCHitN_Ng_z(args->hit, args->N, i);
    ctx->hits->push_back({RTCRayN_tfar(args->ray, args->N, i), RTCHitN_primID(args->hit, args->N, i), facing < 0});
    args->valid[i] = 0;
  }
}

// Closest point on triangle abc to p (Ericson, Real-Time Collision Detection, 5.1.5).
double point_triangle_distance(const double p[3], const Point3& A, const Point3& B, const Point3& C) {
  double a[3], b[3], c[3];
  for (int k = 0; k < 3; ++k) a[k] = A[k], b[k] = B[k], c[k] = C[k];
  auto sub = [](const double* x, const double* y, double* r) { r[0] = x[0] - y[0], r[1] = x[1] - y[1], r[2] = x[2] - y[2]; };
  auto dot = [](const double* x, const double* y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; };
  double ab[3], ac[3], ap[3], bp[3], cp[3], q[3];
  sub(b, a, ab), sub(c, a, ac), sub(p, a, ap);
  auto dist_to = [&](double s, double t) {
    for (int k = 0; k < 3; ++k) q[k] = a[k] + s * ab[k] + t * ac[k] - p[k];
    return std::sqrt(dot(q, q));
  };
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return dist_to(0, 0);
  sub(p, b, bp);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return dist_to(1, 0);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return dist_to(d1 / (d1 - d3), 0);
  sub(p, c, cp);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return dist_to(0, 1);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return dist_to(0, d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return dist_to(1 - w, w);
  }
  const double denom = 1.0 / (va + vb + vc);
  return dist_to(vb * denom, vc * denom);
}

struct ClosestQuery {
  const std::vector<Point3>* positions;
  const std::vector<uint32_t>* triangles;
  const double* p;
  double best;
};

bool closest_callback(RTCPointQueryFunctionArguments* args) {
  auto* q = static_cast<ClosestQuery*>(args->userPtr);
  const uint32_t* t = &(*q->triangles)[3 * args->primID];
  const double d = point_triangle_distance(q->p, (*q->positions)[t[0]], (*q->positions)[t[1]], (*q->positions)[t[2]]);
  if (d < q->best) {
    q->best = d;
    args->query->radius = static_cast<float>(d);
    return true;
  }
  return false;
}

}  // namespace

void check_embree(const char* what) { check_device(what); }

RTCDevice embree_device() {
  static RTCDevice device = [] {
    RTCDevice d = rtcNewDevice(nullptr);
    if (!d) throw std::runtime_error("Embree: cannot create device");
    rtcSetDeviceErrorFunction(d, embree_error, nullptr);
    return d;
  }();
  return device;
}

EmbreeTriangleScene::EmbreeTriangleScene(const std::vector<Point3>& positions, const std::vector<uint32_t>& triangles)
    : positions_(positions), triangles_(triangles) {
  RTCDevice device = embree_device();
  scene_ = rtcNewScene(device);
  // Robust: watertight triangle tests, so a ray through a shared edge never slips between.
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, positions_.data(), 0,
                             sizeof(Point3), positions_.size());
  rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, triangles_.data(), 0,
                             3 * sizeof(uint32_t), triangles_.size() / 3);
  rtcSetGeometryIntersectFilterFunction(geom, record_hit);
  rtcCommitGeometry(geom);
  rtcAttachGeometry(scene_, geom);
  rtcReleaseGeometry(geom);
  rtcCommitScene(scene_);
  check_device("building the Embree triangle scene");
}

EmbreeTriangleScene::~EmbreeTriangleScene() {
  if (scene_) rtcReleaseScene(scene_);
}

bool EmbreeTriangleScene::share_vertex(uint32_t a, uint32_t b) const {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (triangles_[3 * a + i] == triangles_[3 * b + j]) return true;
  return false;
}

std::vector<float> EmbreeTriangleScene::crossings(const float origin[3], const float dir[3], float tfar,
                                                  float merge_eps) const {
  std::vector<Hit> hits;
  AllHitsContext ctx;
  rtcInitIntersectContext(&ctx.base);
  ctx.hits = &hits;
  RTCRayHit rh{};
  rh.ray.org_x = origin[0], rh.ray.org_y = origin[1], rh.ray.org_z = origin[2];
  rh.ray.dir_x = dir[0], rh.ray.dir_y = dir[1], rh.ray.dir_z = dir[2];
  rh.ray.tnear = 0.0f;
  rh.ray.tfar = tfar;
  rh.ray.mask = 0xffffffffu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &ctx.base, &rh);
  std::sort(hits.begin(), hits.end(), [](const Hit& a, const Hit& b) { return a.t < b.t; });
  // A line through a shared edge or vertex is reported by every triangle there: one crossing.
  // Close hits on unrelated triangles (a thin fold), or on neighbours in opposite directions (a
  // line grazing in and out, or touching a ridge) stay separate crossings.
  std::vector<float> merged;
  size_t group = 0;
  for (size_t i = 0; i < hits.size(); ++i) {
    const bool same = !merged.empty() && hits[i].t - hits[group].t <= merge_eps &&
                      hits[i].entering == hits[group].entering && share_vertex(hits[i].prim, hits[group].prim);
    if (same) continue;
    merged.push_back(hits[i].t);
    group = i;
  }
  return merged;
}

double EmbreeTriangleScene::closest_distance(const double p[3]) const {
  ClosestQuery q{&positions_, &triangles_, p, std::numeric_limits<double>::infinity()};
  RTCPointQuery query;
  query.x = static_cast<float>(p[0]), query.y = static_cast<float>(p[1]), query.z = static_cast<float>(p[2]);
  query.time = 0.0f;
  query.radius = std::numeric_limits<float>::infinity();
  RTCPointQueryContext context;
  rtcInitPointQueryContext(&context);
  rtcPointQuery(scene_, &query, &context, closest_callback, &q);
  return q.best;
}

}  // namespace sdb
