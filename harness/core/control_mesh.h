// ControlMesh: the input every scheme and the reference start from. Plain data, no behaviour; part
// of the contract (harness/core), read and checked by harness/mesh.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace sdb {

using Point3 = std::array<float, 3>;

// Which subdivision surface a mesh stands for (and which OpenSubdiv limit a scheme is judged by).
enum class SubdivisionRule { CatmullClark, Loop };

// OpenSubdiv's vertex boundary interpolation (Sdc::Options::VtxBoundaryInterpolation).
enum class BoundaryRule { None, EdgeOnly, EdgeAndCorner };
enum class CreaseMethod { Uniform, Chaikin };
// Catmull-Clark treatment of triangles (Sdc::Options::TriangleSubdivision).
enum class TriangleRule { Catmark, Smooth };

struct EdgeCrease {
  int v0 = 0, v1 = 0;
  float sharpness = 0.0f;
};

struct VertexCorner {
  int vertex = 0;
  float sharpness = 0.0f;
};

struct ControlMesh {
  std::string name;    // manifest name or file stem
  std::string source;  // file path, or "builtin:<generator>"
  std::vector<Point3> positions;
  std::vector<int> face_sizes;
  std::vector<int> face_vertices;  // concatenated, counter-clockwise
  std::vector<EdgeCrease> creases;
  std::vector<VertexCorner> corners;
  std::vector<int> holes;  // face indices
  BoundaryRule boundary = BoundaryRule::EdgeOnly;  // OpenSubdiv's regression default
  CreaseMethod crease_method = CreaseMethod::Uniform;
  TriangleRule triangle_rule = TriangleRule::Catmark;
  // Source line of each face (empty for generated meshes), so that checks made after reading
  // (non-manifold edges, orientation) can still name the line.
  std::vector<int> face_lines;
  // Things the reader kept going past (ignored tags and the like), shown by `info`.
  std::vector<std::string> warnings;
};

inline int num_faces(const ControlMesh& m) { return static_cast<int>(m.face_sizes.size()); }
inline int num_vertices(const ControlMesh& m) { return static_cast<int>(m.positions.size()); }

// Prefix sums of face_sizes: face f's vertices are face_vertices[offsets[f] .. offsets[f+1]).
std::vector<int> face_offsets(const ControlMesh& m);

// "file:line" for face f when known, else the mesh source.
std::string face_location(const ControlMesh& m, int face);

std::string to_string(BoundaryRule rule);

// Axis-aligned bounds of a point set (in double), and its diagonal: the scale deviations and
// tolerances are stated against.
struct Bounds {
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  double diagonal() const;
  double centre(int axis) const { return 0.5 * (lo[axis] + hi[axis]); }
};
Bounds bounds_of(const std::vector<Point3>& points);

}  // namespace sdb
