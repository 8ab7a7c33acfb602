#include "harness/validate/deviation_ply.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

#include "harness/core/errors.h"

namespace sdb {

void write_deviation_ply(const Tessellation& t, const DeviationReport& d, const std::string& path, const Placement& placement) {
  using Mesh = OpenMesh::PolyMesh_ArrayKernelT<>;
  Mesh mesh;
  OpenMesh::VPropHandleT<float> pct, deg;
  mesh.add_property(pct, "deviation_pct");
  mesh.add_property(deg, "normal_deg");
  mesh.property(pct).set_persistent(true);
  mesh.property(deg).set_persistent(true);
  std::vector<Mesh::VertexHandle> vh;
  vh.reserve(t.positions.size());
  for (size_t i = 0; i < t.positions.size(); ++i) {
    const Point3 p = placement.original(t.positions[i]);
    vh.push_back(mesh.add_vertex({p[0], p[1], p[2]}));
    mesh.property(pct, vh.back()) = i < d.vertex_pct.size() ? d.vertex_pct[i] : 0.0f;
    mesh.property(deg, vh.back()) = i < d.vertex_deg.size() ? d.vertex_deg[i] : 0.0f;
  }
  for (size_t i = 0; i + 2 < t.triangles.size(); i += 3)
    mesh.add_face(vh[t.triangles[i]], vh[t.triangles[i + 1]], vh[t.triangles[i + 2]]);
  OpenMesh::IO::Options options(OpenMesh::IO::Options::Custom | OpenMesh::IO::Options::Binary);
  if (!OpenMesh::IO::write_mesh(mesh, path, options)) throw InputError(path, "cannot write the deviation PLY");
}

}  // namespace sdb
