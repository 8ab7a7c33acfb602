#include "harness/reference/embree_scene.h"

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
struct AllHitsContext {
  RTCIntersectContext base;
  EmbreeTriangleScene::LineCrossings* out;
  float edge_eps;
  float origin_norm;  // |origin|: Embree intersects in the ray's frame, so errors scale with it
};

// How far from an edge a hit must be for its barycentrics to be trusted: float rounding of the
// vertices in the ray's frame (~eps (|o| + t)), over the triangle's size L, amplified by
// 1 / |cos| of the angle between the line and the normal (a grazing line sees the triangle edge-on).
float barycentric_uncertainty(float t, float origin_norm, const float ng[3], const float dir[3]) {
  const float ng_len = std::sqrt(ng[0] * ng[0] + ng[1] * ng[1] + ng[2] * ng[2]);  // twice the area
  const float cosine = std::abs(ng[0] * dir[0] + ng[1] * dir[1] + ng[2] * dir[2]) / std::max(ng_len, 1e-30f);
  const float size = std::sqrt(ng_len);
  return 16.0f * 1.2e-7f * (origin_norm + t) / std::max(size * cosine, 1e-30f);
}

// Rejects every hit so traversal continues to the next, counting them on the way.
void record_hit(const RTCFilterFunctionNArguments* args) {
  auto* ctx = reinterpret_cast<AllHitsContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (!args->valid[i]) continue;
    const unsigned N = args->N;
    const float u = RTCHitN_u(args->hit, N, i), v = RTCHitN_v(args->hit, N, i);
    const float ng[3] = {RTCHitN_Ng_x(args->hit, N, i), RTCHitN_Ng_y(args->hit, N, i), RTCHitN_Ng_z(args->hit, N, i)};
    const float dir[3] = {RTCRayN_dir_x(args->ray, N, i), RTCRayN_dir_y(args->ray, N, i), RTCRayN_dir_z(args->ray, N, i)};
    const float tol = std::max(ctx->edge_eps, barycentric_uncertainty(RTCRayN_tfar(args->ray, N, i), ctx->origin_norm, ng, dir));
    ++ctx->out->count;
    if (std::min({u, v, 1.0f - u - v}) < tol) ctx->out->ambiguous = true;
    args->valid[i] = 0;
  }
}

// Closest point on triangle abc to p (Ericson, Real-Time Collision Detection, 5.1.5): its distance,
// and the point as a + s (b - a) + t (c - a) in `st` when asked.
double point_triangle_distance(const double p[3], const Point3& A, const Point3& B, const Point3& C,
                               double* st = nullptr) {
  double a[3], b[3], c[3];
  for (int k = 0; k < 3; ++k) a[k] = A[k], b[k] = B[k], c[k] = C[k];
  auto sub = [](const double* x, const double* y, double* r) { r[0] = x[0] - y[0], r[1] = x[1] - y[1], r[2] = x[2] - y[2]; };
  auto dot = [](const double* x, const double* y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; };
  double ab[3], ac[3], ap[3], bp[3], cp[3], q[3];
  sub(b, a, ab), sub(c, a, ac), sub(p, a, ap);
  auto dist_to = [&](double s, double t) {
    if (st) st[0] = s, st[1] = t;
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
  uint32_t triangle = 0;
  double st[2] = {0, 0};
};

bool closest_callback(RTCPointQueryFunctionArguments* args) {
  auto* q = static_cast<ClosestQuery*>(args->userPtr);
  const uint32_t* t = &(*q->triangles)[3 * args->primID];
  double st[2];
  const double d = point_triangle_distance(q->p, (*q->positions)[t[0]], (*q->positions)[t[1]], (*q->positions)[t[2]], st);
  if (d < q->best) {
    q->best = d;
    q->triangle = args->primID;
    q->st[0] = st[0], q->st[1] = st[1];
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

long positions_out_of_range(const std::vector<Point3>& positions) {
  return std::count_if(positions.begin(), positions.end(), [](const Point3& p) {
    return !(std::abs(p[0]) <= kEmbreeRange && std::abs(p[1]) <= kEmbreeRange && std::abs(p[2]) <= kEmbreeRange);
  });
}

EmbreeTriangleScene::EmbreeTriangleScene(const std::vector<Point3>& positions, const std::vector<uint32_t>& triangles)
    : positions_(positions), triangles_(triangles) {
  // Checked before Embree sees them: past its range it aborts the process (a NaN fails the test too).
  if (const long bad = positions_out_of_range(positions))
    throw std::invalid_argument(std::to_string(bad) + " positions past Embree's range (NaN, infinite or beyond 1e17)");
  // Embree reads shared vertex buffers 16 bytes at a time: the last vertex needs padding after it
  // (valgrind found the read past the end).
  positions_.push_back({0, 0, 0});
  RTCDevice device = embree_device();
  scene_ = rtcNewScene(device);
  // Robust: watertight triangle tests, so a ray through a shared edge never slips between.
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, positions_.data(), 0,
                             sizeof(Point3), positions_.size() - 1);
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

EmbreeTriangleScene::LineCrossings EmbreeTriangleScene::crossings(const float origin[3], const float dir[3], float tfar,
                                                                  float edge_eps) const {
  LineCrossings out;
  AllHitsContext ctx;
  rtcInitIntersectContext(&ctx.base);
  ctx.out = &out;
  ctx.edge_eps = edge_eps;
  ctx.origin_norm = std::sqrt(origin[0] * origin[0] + origin[1] * origin[1] + origin[2] * origin[2]);
  RTCRayHit rh{};
  rh.ray.org_x = origin[0], rh.ray.org_y = origin[1], rh.ray.org_z = origin[2];
  rh.ray.dir_x = dir[0], rh.ray.dir_y = dir[1], rh.ray.dir_z = dir[2];
  rh.ray.tnear = 0.0f;
  rh.ray.tfar = tfar;
  rh.ray.mask = 0xffffffffu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &ctx.base, &rh);
  return out;
}

double EmbreeTriangleScene::closest_distance(const double p[3], double radius_hint) const {
  return closest(p, radius_hint).distance;
}

EmbreeTriangleScene::Closest EmbreeTriangleScene::closest(const double p[3], double radius_hint) const {
  for (double radius : {radius_hint, std::numeric_limits<double>::infinity()}) {
    ClosestQuery q{&positions_, &triangles_, p, radius};
    RTCPointQuery query;
    query.x = static_cast<float>(p[0]), query.y = static_cast<float>(p[1]), query.z = static_cast<float>(p[2]);
    query.time = 0.0f;
    query.radius = static_cast<float>(radius);
    RTCPointQueryContext context;
    rtcInitPointQueryContext(&context);
    rtcPointQuery(scene_, &query, &context, closest_callback, &q);
    if (q.best < radius) return {q.best, q.triangle, q.st[0], q.st[1]};
  }
  return {};
}

}  // namespace sdb
