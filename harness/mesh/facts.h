// MeshFacts: what every report says about a mesh, and the topology checks schemes rely on.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "harness/core/control_mesh.h"

namespace sdb {

struct MeshFacts {
  int vertices = 0, faces = 0, edges = 0;
  std::map<int, int> face_sizes;  // size -> count
  std::map<int, int> valences;    // valence -> count (used vertices only)
  int boundary_edges = 0;
  int boundary_loops = 0;
  int non_manifold_edges = 0;     // used by more than two faces
  // Vertices where the faces around them form more than one fan (two cubes sharing a vertex, a
  // bowtie): a pinch, which no manifold has.
  int non_manifold_vertices = 0;
  int inconsistent_edges = 0;     // two faces traverse the edge in the same direction
  int degenerate_faces = 0;       // a vertex repeated within one face
  int unused_vertices = 0;
  int components = 0;
  int euler = 0;                  // V - E + F over used vertices
  int genus = -1;                 // -1 when undefined (non-manifold or inconsistent orientation)
  bool closed = false;
  bool all_quads = false, all_triangles = false;
  // Regular valence is 4 (interior) / 3 (boundary) for quad-dominant meshes and 6 / 4 for
  // all-triangle meshes; extraordinary vertices differ from it.
  double extraordinary_vertex_fraction = 0.0;
  // Share of quads touching a vertex of valence != 4 (the c-patch paper's "eqs").
  double extraordinary_quad_fraction = 0.0;
  int creased_edges = 0, corners = 0, holes = 0;
  bool manifold() const {
    return non_manifold_edges == 0 && non_manifold_vertices == 0 && inconsistent_edges == 0 && degenerate_faces == 0;
  }
};

MeshFacts compute_facts(const ControlMesh& mesh);

// Throws InputError naming the file and line of the first face that repeats a vertex, makes an
// edge non-manifold or breaks orientation, or pinches a vertex, for schemes that cannot take such meshes.
void require_manifold(const ControlMesh& mesh, const std::string& scheme);

// Six times the enclosed signed volume (faces fanned from their first vertex): positive when a
// closed mesh's faces are oriented outwards.
double signed_volume6(const ControlMesh& mesh);

// Per-vertex valence (number of distinct edges), 0 for unused vertices.
std::vector<int> vertex_valences(const ControlMesh& mesh);

}  // namespace sdb
