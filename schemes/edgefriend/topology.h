// Edge-Friend geometry (Kuth, Oberberger, Chajdas, Meyer, HPG 2023, Section 3): after one
// Catmull-Clark step every face is a quad whose corner 0 is the child of a base vertex and corner
// 2 a face point. Then every edge can be owned by exactly one of its two quads: a quad owns its
// edges 1-2 and 3-0 and names, for each, its "friend", the quad on the other side (encoded
// 2 q' + side: the shared edge is the friend's 2 side -> 2 side + 1). With the friends, one
// invocation per quad computes its face point and its two edges' points, and one per vertex its
// vertex point by walking the ring through the friends: no adjacency but 16 bytes a quad, no
// atomics, every point written once.
//
// Numbering from level d to d + 1 (the paper's): quad q's children are 4 q + i, the one at its
// corner i; old vertex v becomes 4 v (v < Q) or 3 Q + v; quad q's face point is 4 q + 1, the
// points of its edges 0-1 and 2-3 are 4 q + 2 and 4 q + 3 (an edge's point is numbered by the quad
// that does not own it). Children of quad q are numbered as harness/refined/coords.h splits faces.
//
// Boundaries (the paper's Section 3.3): each boundary loop of the base mesh is closed by a "ghost"
// face, so that every edge has two quads and every ring is closed; boundary edges are infinitely
// sharp, so nothing of the mesh reads a ghost's points. Ghost quads come after the mesh's quads on
// every level and are never output.
//
// Made once in prepare(), topology only (the paper's kernel refines topology and points together;
// here the points' part is the frame, as osd-uniform's and halfedge's refiners are made before).
#pragma once

#include <cstdint>
#include <vector>

#include <opensubdiv/far/topologyRefiner.h>

#include "harness/core/control_mesh.h"
#include "harness/refined/face_level.h"

namespace sdb::edgefriend {

using refined::kNone;

// The largest valence the rules' weight tables have (rules.h); a mesh vertex past it is refused.
constexpr int kMaxValence = 1024;

// A quad's two owned edges: friend (2 q' + side) and the edge's sharpness; the paper's uint4.
struct Friends {
  uint32_t friend0;  // across edge 1-2
  float sharpness0;
  uint32_t friend1;  // across edge 3-0
  float sharpness1;
};

struct Level {
  uint32_t num_vertices = 0;  // 3 Q + max(V, Q) of the level before: some numbers are unused (genus > 1)
  uint32_t num_quads = 0, mesh_quads = 0;  // quads [mesh_quads, num_quads) are ghosts
  std::vector<uint32_t> indices;        // 4 a quad
  std::vector<Friends> friends;         // 1 a quad
  std::vector<uint32_t> vertex_corner;  // per vertex: a corner 4 q + slot at it, kNone if in no quad
  std::vector<float> vertex_sharpness;  // per vertex; empty: none on this level
  bool creased = false;                 // an edge or vertex is sharp (boundaries count)
};

// Old vertex v's number on the next level.
inline uint32_t child_of_vertex(uint32_t v, uint32_t quads) { return v < quads ? 4 * v : 3 * quads + v; }
inline uint32_t vertices_after(uint32_t vertices, uint32_t quads) { return 3 * quads + (vertices > quads ? vertices : quads); }

// Sdc::Crease's uniform rule: one less a level, infinite stays.
inline float decay(float s) { return s >= refined::kInfiniteSharpness ? s : (s > 1.0f ? s - 1.0f : 0.0f); }

struct Hierarchy {
  // The base vertices of each boundary loop, in the ghost face's order: its face point is level
  // 1's vertex `first_ghost_point + loop`.
  std::vector<std::vector<uint32_t>> loops;
  uint32_t first_ghost_point = 0;
  std::vector<Level> levels;  // levels[0] is depth 1 (the first step's quads), levels.back() depth k
  // The last level's points in output order: out_index[v] is the output vertex of point v, kNone
  // for a ghost's or unused number; empty where every number is output as it is.
  std::vector<uint32_t> out_index;
  uint32_t out_vertices = 0;
  // The last level's mesh quads as the output's faces: corners through out_index, twins (kNone at
  // the mesh's boundary) and each corner's edge sharpness (empty: smooth).
  std::vector<uint32_t> out_verts, out_twin;
  std::vector<float> out_edge_sharpness, out_vertex_sharpness;
  refined::FaceLevel face_level() const;
};

// Levels 1 .. depth and the output's faces, from OpenSubdiv's level 1 of the mesh (`level1`:
// refined uniformly to 1 with full topology): its quads as OpenSubdiv numbers their vertices
// (children of base vertices first, then of faces, then of edges), the ghosts after them. Throws
// InputError naming the mesh for what the paper's structure does not take.
Hierarchy refine(const ControlMesh& mesh, const OpenSubdiv::Far::TopologyRefiner& level1, int depth);

// Level 1 (depth 1) as the limit plan's early level (harness/refined/limit.h, EarlyLevel): its
// mesh quads as faces in the level's own numbers (a ghost's points are in no face), and each of
// its vertices' number in the output at the hierarchy's depth (kNone: not output).
struct FirstLevelFaces {
  std::vector<uint32_t> verts, twin, last_of;
  std::vector<float> edge_sharpness, vertex_sharpness;
  refined::FaceLevel face_level() const;
};
FirstLevelFaces first_level_faces(const Hierarchy& h);

// Quads and vertices of depth k (ghosts included), for size checks before anything is made.
struct Counts {
  double quads = 0, vertices = 0;
};
Counts counts_at(const ControlMesh& mesh, int depth);

}  // namespace sdb::edgefriend
