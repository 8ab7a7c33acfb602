// openmesh-cc, openmesh-loop: OpenMesh's uniform subdividers (CatmullClarkT on a PolyMesh, LoopT
// on a TriMesh), the peer research code reaches for. Each execute() copies the control mesh into
// a half-edge mesh (OpenMesh subdivides in place), subdivides it k times, and lays the refined
// mesh out as triangles with vertex normals from OpenMesh. No limit projection: the output is the
// refined control mesh, and OpenMesh does not say where a refined vertex lies on the base mesh,
// so the rows measure each vertex's distance to the closest point of the limit surface and the
// Hausdorff distance (SchemeInfo::surface_coords, LimitClaim::Approximates).
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/CatmullClarkT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/LoopT.hh>

#include <algorithm>

#include "harness/core/errors.h"
#include "harness/mesh/facts.h"
#include "schemes/peers/peers.h"

namespace sdb {
namespace {

using PolyMesh = OpenMesh::PolyMesh_ArrayKernelT<>;
using TriMesh = OpenMesh::TriMesh_ArrayKernelT<>;

// The control mesh as OpenMesh's half-edge mesh (used vertices only: an isolated vertex has no
// valence for the subdivision rules).
template <typename Mesh>
Mesh to_openmesh(const ControlMesh& m) {
  Mesh mesh;
  std::vector<typename Mesh::VertexHandle> handle(m.positions.size());
  std::vector<char> used(m.positions.size(), 0);
  for (int v : m.face_vertices) used[v] = 1;
  for (size_t v = 0; v < m.positions.size(); ++v)
    if (used[v]) handle[v] = mesh.add_vertex(typename Mesh::Point(m.positions[v][0], m.positions[v][1], m.positions[v][2]));
  const std::vector<int> offsets = face_offsets(m);
  for (int f = 0; f < num_faces(m); ++f) {
    std::vector<typename Mesh::VertexHandle> face;
    for (int i = offsets[f]; i < offsets[f + 1]; ++i) face.push_back(handle[m.face_vertices[i]]);
    if (!mesh.add_face(face).is_valid())
      throw InputError(face_location(m, f), "OpenMesh cannot add this face to its half-edge mesh (a complex edge or vertex)");
  }
  return mesh;
}

// LoopT tabulates its vertex weights for valences below 50 (init_weights' default) and reads past
// the table at a higher valence: garbage weights, a NaN or a plausible wrong point (openmesh-loop
// on loop_pole64's valence-64 poles, row "ok" as given and NaN on a copy scaled by 1e-6). Sized to
// the mesh's largest valence, which refinement never raises. CatmullClarkT computes its weights.
template <typename Subdivider>
void fit_weights(Subdivider&, size_t) {}
void fit_weights(OpenMesh::Subdivider::Uniform::LoopT<TriMesh>& loop, size_t largest_valence) {
  loop.init_weights(std::max<size_t>(50, largest_valence + 1));
}

template <typename Mesh>
size_t largest_valence(const Mesh& mesh) {
  size_t largest = 0;
  for (auto v : mesh.vertices()) largest = std::max<size_t>(largest, mesh.valence(v));
  return largest;
}

template <typename Mesh, typename Subdivider>
class OpenMeshEvaluation final : public Evaluation {
 public:
  OpenMeshEvaluation(const ControlMesh& mesh, int depth)
      : base_(to_openmesh<Mesh>(mesh)), largest_valence_(largest_valence(base_)), depth_(depth) {}

  void execute() override {
    refined_ = base_;
    Subdivider subdivider;
    fit_weights(subdivider, largest_valence_);
    subdivider.attach(refined_);
    subdivider(static_cast<size_t>(depth_));
    subdivider.detach();
    refined_.request_face_normals();
    refined_.request_vertex_normals();
    refined_.update_normals();
    lay_out();
  }

  const Tessellation& result() override { return out_; }
  size_t bytes_out() const override { return out_.positions.size() * 2 * sizeof(Point3); }

 private:
  void lay_out() {
    out_.positions.resize(refined_.n_vertices());
    out_.normals.resize(refined_.n_vertices());
    for (auto v : refined_.vertices()) {
      const auto p = refined_.point(v);
      const auto n = refined_.normal(v);
      out_.positions[v.idx()] = {float(p[0]), float(p[1]), float(p[2])};
      out_.normals[v.idx()] = {float(n[0]), float(n[1]), float(n[2])};
    }
    out_.triangles.clear();
    for (auto f : refined_.faces()) {
      std::vector<uint32_t> fv;
      for (auto v : refined_.fv_range(f)) fv.push_back(uint32_t(v.idx()));
      for (size_t k = 1; k + 1 < fv.size(); ++k) out_.triangles.insert(out_.triangles.end(), {fv[0], fv[k], fv[k + 1]});
    }
  }

  const Mesh base_;
  size_t largest_valence_;
  Mesh refined_;
  int depth_;
  Tessellation out_;
};

class OpenMeshSubdivider final : public Scheme {
 public:
  explicit OpenMeshSubdivider(SubdivisionRule rule) : rule_(rule) {
    const bool loop = rule == SubdivisionRule::Loop;
    info_.name = loop ? "openmesh-loop" : "openmesh-cc";
    info_.paper = loop ? "peer: OpenMesh 9 Subdivider::Uniform::LoopT" : "peer: OpenMesh 9 Subdivider::Uniform::CatmullClarkT";
    info_.description = "OpenMesh's uniform subdivider to depth k: the refined control mesh, no limit projection";
    info_.role = SchemeRole::Peer;
    info_.peer = loop ? "osd-uniform-loop" : "osd-uniform";  // OpenSubdiv's refinement of the same depth
    info_.surface_coords = false;
    info_.reference = rule;
    info_.limit = LimitClaim::Approximates;  // judged by nearest points and Hausdorff
    info_.level_kind = LevelKind::Depth;
    info_.backends = {Backend::Cpu};  // OpenMesh's subdividers are serial
    info_.default_levels = {1, 2, 3, 4};
    info_.accepts.faces = loop ? MeshRequirements::Faces::TrianglesOnly : MeshRequirements::Faces::Any;
    info_.accepts.manifold = true;  // a half-edge mesh
    info_.accepts.creases = false;  // OpenMesh's rules know no creases
    info_.accepts.holes = false;
  }
  const SchemeInfo& info() const override { return info_; }
  std::optional<std::string> unsupported(const RunRequest& r) const override {
    if (r.level < 1 || r.level > 8) return "depth must be 1..8";
    return std::nullopt;
  }
  std::unique_ptr<Evaluation> prepare(const ControlMesh& mesh, const RunRequest& r) const override {
    // OpenMesh's subdividers have one boundary rule and always refine every face: an open mesh
    // tagged `interpolateboundary 0` (no surface on its boundary faces) or 1 (corners pinned) is a
    // tag they cannot honour, and their output would pass for the surface the tag asks for.
    if (mesh.boundary != BoundaryRule::EdgeOnly && compute_facts(mesh).boundary_edges > 0)
      throw InputError(mesh.source, info_.name + " cannot honour the tag 'interpolateboundary " +
                                        (mesh.boundary == BoundaryRule::None ? "0' (none" : "1' (edge-and-corner") +
                                        "): OpenMesh's subdividers have one boundary rule");
    if (rule_ == SubdivisionRule::Loop)
      return std::make_unique<OpenMeshEvaluation<TriMesh, OpenMesh::Subdivider::Uniform::LoopT<TriMesh>>>(mesh, r.level);
    return std::make_unique<OpenMeshEvaluation<PolyMesh, OpenMesh::Subdivider::Uniform::CatmullClarkT<PolyMesh>>>(mesh,
                                                                                                               r.level);
  }

 private:
  SubdivisionRule rule_;
  SchemeInfo info_;
};

}  // namespace

std::unique_ptr<Scheme> make_openmesh_subdivider(SubdivisionRule rule) {
  return std::make_unique<OpenMeshSubdivider>(rule);
}

}  // namespace sdb
