// A few faces of a refinement level cut out as a mesh of their own, with their sharpness, holes
// and points (double): what local refinement refines instead of the whole mesh. A face's limit
// surface depends on the faces around its corners alone, and so do those faces' children around
// the face's children; Far refines the cut-out exactly there (vertex_limit.h, the yardstick's
// descent in limit_evaluator.cpp).
#pragma once

#include <opensubdiv/far/topologyLevel.h>
#include <opensubdiv/far/topologyRefiner.h>
#include <opensubdiv/sdc/options.h>

#include <array>
#include <memory>
#include <vector>

#include "harness/core/control_mesh.h"

namespace sdb {

using Point3d = std::array<double, 3>;

struct LocalMesh {
  std::vector<int> face_sizes, face_vertices, holes;
  std::vector<int> crease_pairs, corner_vertices;
  std::vector<float> crease_weights, corner_weights;
  std::vector<Point3d> points;
  // Per vertex, where the caller marks some (the yardstick: non-manifold ones, which a cut-out
  // cannot tell from its own border), carried to the children by refine_marks.
  std::vector<char> marks;
};

// `faces` of `level` (each once), their vertices numbered in order of first use; `local_of`, when
// given, receives the local number of each of the level's vertices used (-1 elsewhere).
LocalMesh cut_faces(const OpenSubdiv::Far::TopologyLevel& level, const std::vector<Point3d>& points,
                    const std::vector<int>& faces, std::vector<int>* local_of = nullptr,
                    const std::vector<char>* marks = nullptr);

// The marks of a refined level: a marked vertex's child, and the point of an edge between two
// marked vertices.
std::vector<char> refine_marks(const OpenSubdiv::Far::TopologyRefiner& r, const std::vector<char>& marks);

// A vertex's ring as a mesh of its own: vertex 0 the centre, 1 + i the far end of edge i
// (counter-clockwise), under Catmull-Clark 1 + edges + i the corner opposite it in face i (between
// edges i and i + 1; quads only); edge i creased by edge_sharpness[i] where above 0, the centre a
// corner of `vertex_sharpness` where above 0; points at the origin (the ring's masks are weights).
LocalMesh ring_mesh(int edges, int faces, const std::vector<float>& edge_sharpness, float vertex_sharpness,
                    bool catmark);

// The faces around face f's corners (f first).
std::vector<int> faces_around(const OpenSubdiv::Far::TopologyLevel& level, int f);

std::unique_ptr<OpenSubdiv::Far::TopologyRefiner> refiner_of(const LocalMesh& m, SubdivisionRule rule,
                                                             const OpenSubdiv::Sdc::Options& options);

// Refines `r` (not refined yet) one level, full topology, and returns the new level's points.
std::vector<Point3d> refine_once(OpenSubdiv::Far::TopologyRefiner& r, const std::vector<Point3d>& points);

}  // namespace sdb
