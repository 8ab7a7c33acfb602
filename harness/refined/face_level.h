// One level of a mesh refined by splitting every face at its corners, where every face has the
// same number of corners: quads after a Catmull-Clark step, triangles under Loop. What the
// uniform-refinement peers (schemes/halfedge, schemes/edgefriend) hand to this module for their
// output: the triangles, the SurfaceCoords and the limit projection with Far's masks.
//
// Corner c of face f is c = face_size * f + i (i = 0 .. face_size - 1, counter-clockwise); the
// edge from corner c runs verts[c] -> verts[next(c)]; twin[c] is the corner that runs the same
// edge the other way in the neighbouring face, kNone on a boundary. This is Dupuy and Vanhoey's
// halfedge of a semi-regular mesh (the halfedge *is* the corner).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

namespace sdb::refined {

constexpr uint32_t kNone = 0xffffffffu;
// OpenSubdiv's infinite sharpness (Sdc::Crease::SHARPNESS_INFINITE): boundary edges carry it.
constexpr float kInfiniteSharpness = 10.0f;

// Quads and triangles by bit operations and a division by a constant (a division by a run-time
// face size in every step of a ring walk was most of the limit pass's time on the sword).
inline uint32_t next_corner(uint32_t c, uint32_t face_size) {
  if (face_size == 4) return (c & ~3u) | ((c + 1) & 3u);
  if (face_size == 3) return c % 3 == 2 ? c - 2 : c + 1;
  const uint32_t i = c % face_size;
  return c - i + (i + 1 == face_size ? 0 : i + 1);
}
inline uint32_t prev_corner(uint32_t c, uint32_t face_size) {
  if (face_size == 4) return (c & ~3u) | ((c + 3) & 3u);
  if (face_size == 3) return c % 3 == 0 ? c + 2 : c - 1;
  const uint32_t i = c % face_size;
  return c - i + (i == 0 ? face_size - 1 : i - 1);
}

struct FaceLevel {
  uint32_t face_size = 4;
  uint32_t num_vertices = 0;
  const uint32_t* verts = nullptr;  // face_size * num_faces
  const uint32_t* twin = nullptr;
  uint64_t num_corners = 0;
  // Sharpness of the edge from corner c (boundary edges: kInfiniteSharpness), and of vertex v;
  // null: all smooth.
  std::function<float(uint32_t corner)> edge_sharpness;
  std::function<float(uint32_t vertex)> vertex_sharpness;
};

// A corner at every vertex, the one a walk around it starts from: at a boundary vertex the corner
// whose edge is the leading boundary edge (its twin is kNone), so that turning counter-clockwise
// (c -> twin[prev(c)]) sweeps every face. kNone for a vertex in no face.
std::vector<uint32_t> vertex_corners(const FaceLevel& level);

}  // namespace sdb::refined
