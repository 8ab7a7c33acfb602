// The halfedge hierarchy of Dupuy and Vanhoey: every level's halfedges (twin, vertex, edge), made
// from the one before by the refinement rule alone (HPG 2021 Section 4 for Catmull-Clark, EG 2022
// Section 3 for Loop): halfedge h of level d has the four halfedges 4h + j (Catmull-Clark) or
// 3h + j and 3H + h (Loop) at level d + 1, their twins, vertices and edges closed-form functions
// of h's. Vertices of level d + 1 are [level d's vertices, (Catmull-Clark) one per face, one per
// edge]; edge e's halves are edges 2e and 2e + 1, the edges inside faces follow.
//
// Sharpness rides along per edge and per vertex as OpenSubdiv refines it (Sdc::Crease, uniform or
// Chaikin): the papers' crease structures carry the same values, but Far's Chaikin rule reads every
// edge at the vertex, not a crease's two neighbours (README.md, "What differs").
//
// Made once in prepare(): topology depends on nothing the frame changes.
#pragma once

#include <cstdint>
#include <vector>

#include "harness/core/control_mesh.h"
#include "harness/refined/face_level.h"

namespace sdb::halfedge {

using refined::kNone;

struct Level {
  uint32_t num_vertices = 0, num_faces = 0, num_edges = 0;
  uint64_t num_halfedges = 0;
  // Faces of `face_size` corners, halfedge h the corner h of face h / face_size; 0 on a base level
  // of mixed faces, whose next, prev and face are the arrays below.
  uint32_t face_size = 0;
  std::vector<uint32_t> twin, vert, edge;
  std::vector<uint32_t> next_of, prev_of, face_of, face_first;  // mixed base level only (face_first: F + 1)
  std::vector<uint32_t> edge_corner;    // per edge: its halfedge (the smaller of the two)
  std::vector<uint32_t> vertex_corner;  // per vertex: where walks start (refined::vertex_corners)
  std::vector<float> edge_sharpness, vertex_sharpness;  // empty: none on this level

  uint32_t next(uint32_t h) const { return face_size ? refined::next_corner(h, face_size) : next_of[h]; }
  uint32_t prev(uint32_t h) const { return face_size ? refined::prev_corner(h, face_size) : prev_of[h]; }
  uint32_t face(uint32_t h) const { return face_size == 4 ? h >> 2 : face_size == 3 ? h / 3 : face_of[h]; }
  float sharpness_of_edge(uint32_t e) const { return edge_sharpness.empty() ? 0.0f : edge_sharpness[e]; }
  float sharpness_of_vertex(uint32_t v) const { return vertex_sharpness.empty() ? 0.0f : vertex_sharpness[v]; }
  // The face-level view of this level (corners = halfedges), for the limit and the output.
  refined::FaceLevel face_level() const;
};

struct Hierarchy {
  SubdivisionRule rule = SubdivisionRule::CatmullClark;
  // The mesh's vertex of each base vertex: those in no face are left out (they have no limit,
  // and no halfedge); empty where every vertex is in a face.
  std::vector<uint32_t> base_vertices;
  std::vector<Level> levels;  // 0 .. depth
  // Whether any level below the last has sharpness (boundaries count): the rules' crease path.
  std::vector<char> creased;
};

// Level 0 from the mesh as accept_mesh gave it (manifold, consistently oriented). Throws InputError
// naming the mesh for what the rules here do not take: a boundary under OpenSubdiv's boundary
// rule "none" (its faces become holes), Catmull-Clark's "smooth triangle" rule.
// `base_vertices` as Hierarchy::base_vertices.
Level base_level(const ControlMesh& mesh, SubdivisionRule rule, std::vector<uint32_t>* base_vertices = nullptr);

// Levels 1 .. depth. Topology only: no positions.
Hierarchy refine(const ControlMesh& mesh, SubdivisionRule rule, int depth);

// Halfedges, vertices, edges and faces of level `depth`, from level 0's without refining (for
// size checks before anything is made).
struct Counts {
  double halfedges = 0, vertices = 0, edges = 0, faces = 0;
};
Counts counts_at(const ControlMesh& mesh, SubdivisionRule rule, int depth);

}  // namespace sdb::halfedge
