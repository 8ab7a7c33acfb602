// OpenSubdiv 3.5.0's Bfr mis-builds one kind of irregular patch, and Debian 12 ships 3.5.0.
// IrregularPatchBuilder::Build gathers a face's sharp edges into a buffer; where the face's
// neighbourhood overlaps itself (a corner whose manifold fan is two faces, closed) and has
// boundary vertices, sharpenBoundaryControlEdges then writes the boundary edges from the start of
// that buffer instead of after the gathered ones, and counts both: the tail of the buffer is
// uninitialised, Far reads it as crease vertex indices: wrong creases, or a segfault in
// Vtr::Level::findEdge (AddressSanitizer, the corpus sweep). OpenSubdiv's fix (51eb6a04, 3.5.1:
// "Fix bug in Bfr::SurfaceFactory with valence-2 interior vertex") came with catmark_val2_interior.
// The harness cannot reach that buffer, so it refuses such meshes wherever Bfr would build them.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "harness/core/control_mesh.h"

namespace sdb {

// Where `mesh` has a face that OpenSubdiv 3.5.0's Bfr would build wrongly: a face with a corner
// whose fan of faces (crossing only edges with two faces) closes after two faces, a corner whose
// fan is open, and a sharp edge (creased, or with more than two faces) at one of its corners. The
// test errs on the side of refusing. Returns a message naming the face's line, or nothing.
std::optional<std::string> bfr_overlapping_patch_defect(const ControlMesh& mesh);

// The same test per face: 1 where Bfr would build the face from uninitialised memory.
std::vector<char> bfr_defect_faces(const ControlMesh& mesh);

}  // namespace sdb
