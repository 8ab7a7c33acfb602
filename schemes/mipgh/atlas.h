// The D-atlas (Shiue, Goel, Peters 2003, Section 3.2, Figures 9-12): the input mesh's connectivity
// as charts, fixed after initialization. One D-facet per input quad or triangle, D-edges as pairs
// of halfedges, D-vertices as rings of (D-facet, corner) pairs. Plain data; nothing here knows
// positions or levels (lod.h lays the levels out).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "harness/core/control_mesh.h"

namespace sdb::mipgh {

// A D-facet's side k runs from its corner k to corner k + 1 (counter-clockwise, Figure 10). The
// halfedge (facet, k) is that side; it "points to" corner k + 1.
struct HalfEdge {
  int32_t facet = -1;  // -1: none (the second halfedge of a global boundary edge)
  int32_t side = 0;
  bool null() const { return facet < 0; }
};

// Figure 11: the major halfedge orients the edge: its nodes are numbered from the major side's
// first corner. `minor` runs the other way; null on a global boundary.
struct DEdge {
  HalfEdge major, minor;
};

struct DAtlas {
  int num_vertices = 0;  // D-vertices: one per input vertex, same index
  std::vector<uint8_t> facet_size;                    // 4: quad, 3: triangle
  std::vector<int32_t> quads_before;                  // quads among D-facets 0 .. f - 1 (size + 1)
  std::vector<std::array<int32_t, 4>> facet_corners;  // input vertex at corner k, counter-clockwise
  std::vector<std::array<int32_t, 4>> facet_edges;    // the D-edge of side k
  std::vector<std::array<uint8_t, 4>> facet_side_minor;  // 1 where side k is its edge's minor halfedge
  std::vector<uint8_t> facet_hole;                    // refined, but compiled into no primitive
  std::vector<DEdge> edges;
  // Figure 12: D-vertex v's ring is ring[ring_offsets[v] .. ring_offsets[v + 1]): the (D-facet,
  // corner) pairs around it. Departure: counter-clockwise (Sdc's order, so that its crease masks
  // read the ring as they are written), where the paper lists them clockwise. On a global
  // boundary the ring starts at the facet whose outgoing side (corner -> corner + 1) is the
  // boundary.
  std::vector<int32_t> ring_offsets;
  std::vector<HalfEdge> ring;  // side = the corner of `facet` at the vertex
  std::vector<uint8_t> vertex_boundary;
  // A vertex whose faces form several fans (a non-manifold vertex, two cones meeting at a point):
  // the ring holds its first fan only. Far makes such a vertex an infinitely sharp corner, whose
  // masks read no ring; the processor checks that the tags say so.
  std::vector<uint8_t> vertex_fans;

  int num_facets() const { return static_cast<int>(facet_corners.size()); }
  int next(int f, int k) const { return k + 1 == facet_size[f] ? 0 : k + 1; }
  int prev(int f, int k) const { return k == 0 ? facet_size[f] - 1 : k - 1; }
  int num_edges() const { return static_cast<int>(edges.size()); }
  int valence(int v) const { return ring_offsets[v + 1] - ring_offsets[v]; }
};

// Which D-facets a mesh shader takes (R1): the harness quadrangulates or refuses first; this is
// the scheme's own check.
enum class FacetKinds { Quads, Triangles, QuadsAndTriangles };

// Throws InputError naming the face's line where the mesh is not an oriented manifold of the
// facets `kinds` allows.
DAtlas build_atlas(const ControlMesh& mesh, FacetKinds kinds = FacetKinds::Quads);

}  // namespace sdb::mipgh
