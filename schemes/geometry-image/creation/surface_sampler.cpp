#include "schemes/geometry-image/creation/surface_sampler.h"

#include <embree3/rtcore.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace sdb::gim {

struct SurfaceSampler::Impl {
  const TriangleMesh& mesh;
  const std::vector<Vec3d>& sphere;
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;

  Impl(const TriangleMesh& m, const std::vector<Vec3d>& s) : mesh(m), sphere(s) {}
  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }

  // Ray from the centre along d: {triangle, u, v} or triangle -1 when it slips through.
  bool cast(const Vec3d& d, unsigned& prim, float& u, float& v) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh{};
    rh.ray.org_x = rh.ray.org_y = rh.ray.org_z = 0.0f;
    rh.ray.dir_x = static_cast<float>(d[0]);
    rh.ray.dir_y = static_cast<float>(d[1]);
    rh.ray.dir_z = static_cast<float>(d[2]);
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = std::numeric_limits<float>::infinity();
    rh.ray.mask = 0xffffffffu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    prim = rh.hit.primID, u = rh.hit.u, v = rh.hit.v;
    return true;
  }
};

SurfaceSampler::SurfaceSampler(const TriangleMesh& mesh, const std::vector<Vec3d>& sphere)
    : impl_(std::make_unique<Impl>(mesh, sphere)) {
  impl_->device = rtcNewDevice("threads=1");
  if (!impl_->device) throw std::runtime_error("Embree: cannot create a device");
  impl_->scene = rtcNewScene(impl_->device);
  // Robust traversal: a ray through a shared edge hits one of its triangles, never neither.
  rtcSetSceneFlags(impl_->scene, RTC_SCENE_FLAG_ROBUST);
  RTCGeometry geometry = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                               3 * sizeof(float), sphere.size()));
  for (size_t i = 0; i < sphere.size(); ++i)
    for (int k = 0; k < 3; ++k) vertices[3 * i + k] = static_cast<float>(sphere[i][k]);
  auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                 3 * sizeof(unsigned), mesh.triangles.size()));
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) indices[3 * t + k] = static_cast<unsigned>(mesh.triangles[t][k]);
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(impl_->scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(impl_->scene);
}

SurfaceSampler::~SurfaceSampler() = default;

SurfaceSampler::Location SurfaceSampler::locate(const Vec3d& d) const {
  unsigned prim = 0;
  float u = 0, v = 0;
  bool hit = impl_->cast(d, prim, u, v);
  // Float rounding can leave a pinhole where many thin triangles meet: nudge the direction.
  for (int attempt = 1; !hit && attempt <= 8; ++attempt) {
    const double e = 1e-6 * attempt;
    hit = impl_->cast({d[0] + e, d[1] - 0.5 * e, d[2] + 0.25 * e}, prim, u, v);
  }
  if (!hit) throw std::runtime_error("surface sampling: a ray from the centre missed the spherical triangulation");
  return {static_cast<int>(prim), u, v};
}

}  // namespace sdb::gim
