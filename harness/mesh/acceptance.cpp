#include "harness/mesh/acceptance.h"

#include <algorithm>

#include "harness/core/errors.h"
#include "harness/mesh/facts.h"
#include "harness/mesh/quadrangulate.h"
#include "harness/mesh/split_polygons.h"

namespace sdb {

namespace {

template <class Refuse>
void check_sizes(const MeshFacts& facts, const MeshRequirements& req, Refuse refuse) {
  if (!facts.face_sizes.empty() && facts.face_sizes.rbegin()->first > req.max_face_size)
    refuse("a face has " + std::to_string(facts.face_sizes.rbegin()->first) + " vertices, over the " +
           std::to_string(req.max_face_size) + " the scheme takes");
  if (!facts.valences.empty() && facts.valences.rbegin()->first > req.max_valence)
    refuse("a vertex has valence " + std::to_string(facts.valences.rbegin()->first) + ", over the " +
           std::to_string(req.max_valence) + " the scheme takes");
}

}  // namespace

ControlMesh accept_mesh(const ControlMesh& mesh, const SchemeInfo& info) { return accept_mesh(mesh, info, compute_facts(mesh)); }

ControlMesh accept_mesh(const ControlMesh& mesh, const SchemeInfo& info, const MeshFacts& facts) {
  const MeshRequirements& req = info.accepts;
  auto refuse = [&](const std::string& why) -> void {
    throw InputError(mesh.source, info.name + " cannot take mesh '" + mesh.name + "': " + why);
  };
  if (req.manifold) require_manifold(mesh, info.name);
  if (req.closed && facts.boundary_edges > 0)
    refuse("it has " + std::to_string(facts.boundary_edges) + " boundary edges and the scheme needs a closed mesh");
  if (req.genus0 && facts.genus != 0) refuse("genus " + std::to_string(facts.genus) + ", the scheme needs genus 0");
  if (req.genus0 && facts.components != 1) refuse(std::to_string(facts.components) + " components, the scheme needs one");
  if (!req.creases && (facts.creased_edges > 0 || !mesh.corners.empty()))
    refuse("it has crease or corner tags, which the scheme does not honour");
  if (!req.holes && !mesh.holes.empty()) refuse("it has hole tags, which the scheme does not honour");
  if (!mesh.holes.empty() && static_cast<int>(mesh.holes.size()) >= facts.faces) {
    std::vector<char> hole(facts.faces, 0);
    for (int h : mesh.holes) hole[h] = 1;
    if (std::count(hole.begin(), hole.end(), 1) == facts.faces) refuse("every face is a hole: there is no surface");
  }
  check_sizes(facts, req, refuse);
  using F = MeshRequirements::Faces;
  if (req.faces == F::TrianglesOnly && !facts.all_triangles) refuse("the scheme takes triangle meshes only");
  if (req.faces == F::QuadsOnly && !facts.all_quads) {
    if (!req.quadrangulate) refuse("the scheme takes quad meshes only");
    // Quadrangulation turns an n-gon into a valence-n vertex: refused before the work, not after.
    if (facts.face_sizes.rbegin()->first > req.max_valence)
      refuse("a face of " + std::to_string(facts.face_sizes.rbegin()->first) + " vertices becomes a vertex of that valence, over the " +
             std::to_string(req.max_valence) + " the scheme takes");
    ControlMesh quads = quadrangulate(mesh);
    quads.warnings.push_back("quadrangulated by one Catmull-Clark step for " + info.name);
    return quads;
  }
  if (req.split_polygons && !facts.face_sizes.empty() && facts.face_sizes.rbegin()->first > 4) {
    ControlMesh split = split_polygons(mesh);
    split.warnings.push_back("faces of more than four sides split into quads and a triangle for " + info.name);
    return split;
  }
  return mesh;
}

}  // namespace sdb
