// PLY through OpenMesh's reader. OpenMesh's ImporterT repairs non-manifold input by
// duplicating vertices; we intercept faces before that happens and keep the file's data exactly,
// so non-manifold input is reported instead of silently changed. PLY is checked first
// (ply_check.cpp), so OpenMesh only ever sees a file whose header tells the truth.
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/IO/importer/ImporterT.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <sstream>

#include "harness/core/errors.h"
#include "harness/mesh/mesh_io.h"
#include "harness/mesh/ply_check.h"

namespace sdb {
namespace {

using OmMesh = OpenMesh::PolyMesh_ArrayKernelT<>;

class RawImporter : public OpenMesh::IO::ImporterT<OmMesh> {
 public:
  explicit RawImporter(OmMesh& mesh) : ImporterT<OmMesh>(mesh) {}

  OpenMesh::FaceHandle add_face(const VHandles& idx) override {
    face_sizes.push_back(static_cast<int>(idx.size()));
    for (auto vh : idx) face_vertices.push_back(vh.idx());
    return OpenMesh::FaceHandle();  // never hand the face to the half-edge kernel
  }

  std::vector<int> face_sizes, face_vertices;
};

// OpenMesh reports on its own streams ("The reader encountered invalid faces..."); every error it
// could name is found and named with its line before it runs, so its streams stay shut.
void silence_openmesh() {
  static const bool once = [] {
    omerr().disable();
    omout().disable();
    omlog().disable();
    return true;
  }();
  (void)once;
}

}  // namespace

ControlMesh read_openmesh_file(const std::string& path, std::string_view data) {
  silence_openmesh();
  // Checked whatever the extension's case (a ".Ply" once went to OpenMesh unchecked).
  PlyLayout layout = check_ply(data, path);

  OmMesh om;
  RawImporter importer(om);
  OpenMesh::IO::Options opt;
  std::istringstream lf(with_lf_line_ends(data, layout));
  if (!OpenMesh::IO::IOManager().read(lf, "ply", importer, opt)) throw InputError(path, "OpenMesh could not parse the file");

  ControlMesh m;
  m.source = path;
  // Vertices go into OpenMesh's kernel unchanged (only add_face would duplicate them).
  for (const auto& vh : om.vertices()) {
    const auto& p = om.point(vh);
    m.positions.push_back({p[0], p[1], p[2]});
  }
  m.face_sizes = std::move(importer.face_sizes);
  m.face_vertices = std::move(importer.face_vertices);
  if (static_cast<long>(m.positions.size()) != layout.vertices || static_cast<long>(m.face_sizes.size()) != layout.faces)
    throw InputError(path, "OpenMesh read " + std::to_string(m.positions.size()) + " vertices and " +
                               std::to_string(m.face_sizes.size()) + " faces, the header announces " +
                               std::to_string(layout.vertices) + " and " + std::to_string(layout.faces));
  m.face_lines = std::move(layout.face_lines);
  check_mesh_data(m);
  return m;
}

}  // namespace sdb
