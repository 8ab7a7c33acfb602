// GeometryImage and the X-cut symmetry (Losasso et al. 2003, Section 3).
//
// An image of n x n samples (n odd) holds the control points of one closed bicubic B-spline patch.
// Image coordinates are (x, y), 0 <= x, y < n, x along the image's s axis (columns) and y along
// its t axis (rows); sample (x, y) is samples[y * n + x]. With h = (n - 1) / 2 the cut vertices
// are a = (h, 0), b = (n-1, h), c = (h, n-1), d = (0, h), and the four corners fuse into x.
//
// The paper's padding rules are four 180-degree rotations of the image plane, about a, b, c and d:
//   (x, y) -> (2h - x, -y)            about a     g[x][-1]  = g[n-1-x][1]
//   (x, y) -> (2(n-1) - x, 2h - y)    about b     g[n][y]   = g[n-2][n-1-y]
//   (x, y) -> (2h - x, 2(n-1) - y)    about c     g[x][n]   = g[n-1-x][n-2]
//   (x, y) -> (-x, 2h - y)            about d     g[-1][y]  = g[1][n-1-y]
// They generate every identification of the closed surface: two positions that one of them maps
// onto each other hold the same control point. Because the identifications are point reflections
// (no mirror flips), a mask that is point-symmetric and summed in point-symmetric order gives
// bit-identical results at identified positions; masks.h relies on this.
#pragma once

#include <array>
#include <vector>

#include "harness/core/control_mesh.h"

namespace sdb::gim {

struct GeometryImage {
  int size = 0;                  // n: samples per side, odd, >= 3
  std::vector<Point3> samples;   // row-major, samples[y * size + x]

  GeometryImage() = default;
  explicit GeometryImage(int n) : size(n), samples(static_cast<size_t>(n) * n, Point3{0, 0, 0}) {}
  Point3& at(int x, int y) { return samples[static_cast<size_t>(y) * size + x]; }
  const Point3& at(int x, int y) const { return samples[static_cast<size_t>(y) * size + x]; }
};

struct ImagePos {
  int x = 0, y = 0;
  bool operator==(const ImagePos&) const = default;
};

// The identifications of an n x n image: which closed-mesh vertex each image or padded position
// is, and where the cut vertices sit.
class CutSymmetry {
 public:
  explicit CutSymmetry(int n);  // throws std::invalid_argument unless n is odd and >= 3

  int size() const { return n_; }
  int half() const { return (n_ - 1) / 2; }
  // The position inside the image, [0, n)^2, that a padded position (any integers, applying the
  // padding rules transitively) is identified with. Not yet canonical among fused border samples.
  ImagePos fold(int x, int y) const;
  // The canonical representative of a position among all positions identified with it: the
  // four corners -> (0, 0); a side sample -> the one of its mirror pair nearer the side's start.
  ImagePos canonical(int x, int y) const;
  bool is_canonical(int x, int y) const { return canonical(x, y) == ImagePos{x, y}; }
  // Closed-mesh vertex of a (padded) position: canonical positions numbered in row-major order.
  int vertex(int x, int y) const;
  int num_vertices() const { return num_vertices_; }  // n^2 - 2n + 3
  // a, b, c, d (image positions) and their closed-mesh vertices.
  std::array<ImagePos, 4> cut_vertices() const;
  // The four vertices that equation (2) averages for cut vertex i (0..3 = a, b, c, d): the other
  // vertices of its two faces in the closed mesh, as image positions.
  std::array<ImagePos, 4> cut_vertex_neighbours(int i) const;
  // Inward unit step (into the image) and the along-border step u used by the cut-vertex
  // tangents (see masks.h), for cut vertex i.
  ImagePos inward(int i) const;
  ImagePos along(int i) const;

 private:
  int n_;
  int num_vertices_ = 0;
  std::vector<int> vertex_of_;  // n * n
};

// Positions identified by the cut hold bit-identical values (true after construction from a
// closed mesh, and after every subdivision step). Returns the first offending pair, if any.
struct SymmetryViolation {
  ImagePos a, b;
};
std::vector<SymmetryViolation> cut_symmetry_violations(const GeometryImage& image, size_t max_report = 8);

// Copies the canonical sample over every sample identified with it, making the image satisfy
// the cut symmetry exactly.
void symmetrize(GeometryImage& image);

// Equation (2): moves each cut vertex a, b, c, d to the centroid of its four neighbours, which
// makes the limit surface C1 there (the paper's appendix).
void enforce_cut_vertex_centroids(GeometryImage& image);

// Maximum distance of a cut vertex from the centroid of its neighbours (0 after enforcing).
double cut_vertex_centroid_residual(const GeometryImage& image);

}  // namespace sdb::gim
