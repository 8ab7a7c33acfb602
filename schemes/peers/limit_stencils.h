// What osd-stencil and osd-glcompute evaluate, made in prepare (once per topology): the limit
// position and both tangents at every vertex of uniform refinement to depth k, as one
// Far::LimitStencilTable over the control points, beside the triangles and SurfaceCoords of that
// refinement (osd-uniform's output layout, vertex for vertex).
#pragma once

#include <opensubdiv/far/stencilTable.h>

#include <cstddef>
#include <memory>
#include <vector>

#include "harness/core/control_mesh.h"
#include "harness/core/scheme.h"
#include "harness/core/tessellation.h"

namespace sdb {

// What depends on the mesh's topology only (faces, tags, options; never the positions), so that
// one copy serves every mesh of that topology: a scaled or moved copy, and osd-stencil and
// osd-glcompute on the same mesh.
struct LimitStencils {
  int control_points = 0;
  size_t vertices = 0;  // of depth-k refinement
  // Limit stencil j gives vertex limit_vertices[j]; every vertex that has a limit patch.
  std::unique_ptr<const OpenSubdiv::Far::LimitStencilTable> table;
  std::vector<uint32_t> limit_vertices;
  bool all_vertices_have_limits() const { return limit_vertices.size() == vertices; }
  // Vertices with no limit patch (only on holes, or on the faces an EdgeNone boundary leaves
  // without a limit): their refined position, from these stencils (row = vertex), tangents zero.
  std::vector<uint32_t> refined_only;
  std::unique_ptr<const OpenSubdiv::Far::StencilTable> refined;
  size_t bytes() const;
};

// What prepare starts from: the triangles and SurfaceCoords of depth-k refinement (positions and
// normals left empty), the evaluation's own, and the tables, shared.
struct PreparedStencils {
  Tessellation topology;
  std::shared_ptr<const LimitStencils> stencils;
};

// Far::LimitStencilTableFactory evaluates the patches of a refiner. A uniformly refined one has
// bilinear patches only, so the table is made on a second, adaptively refined refiner, at the
// SurfaceCoords of the uniform refinement's vertices. Isolated to depth + 1 on smooth meshes:
// every depth-k vertex away from an extraordinary vertex then lies on regular B-spline patches,
// and an extraordinary vertex itself at an end cap's corner, which is its limit point (exact to
// 1.4e-7 of the diagonal on pole8). Next to creases, corners and boundaries the patches converge
// only as the isolation level L grows (measured at depth 2: catmark_hole_test2 4.6e-4 of the
// diagonal at L = 6, 6e-8 at 8; catmark_dart_edgeonly 7e-6 at 6, 4.6e-7 at 8; a semi-sharp crease
// is exact once L exceeds its sharpness), so meshes with such features are isolated to 8. Level
// 10, OpenSubdiv's maximum, took Far::LimitStencilTableFactory over ten minutes on one corpus shape
// (appendLocalPointStencilTable); single-crease patches were worse (3e-3 on catmark_cube_creases1).
// The factory factorises every level into stencils over the control points itself.
//
// Made in prepare, never in the timed execute. The tables of the last topologies asked for are
// kept, up to kKeptStencilBytes, and served again for the same topology (content_hash's FNV-1a of
// the faces, tags, options, rule and depth finds an entry; those bytes compared in full accept
// it): Far's factory costs 38 CPU-s at loop_pole360's valence-360 vertex, which a validation of
// the mesh and its scaled copies, or of both peers, would otherwise pay each time.
PreparedStencils limit_stencils(const ControlMesh& mesh, SubdivisionRule rule, int depth);
// Tables past this size are made for their run alone (the sword at depth 4: 5.5 GB): keeping
// them would take memory from the runs after.
constexpr size_t kKeptStencilBytes = size_t(256) << 20;

// Creases, corners, holes or a boundary: what needs the full isolation level.
bool has_sharp_features(const ControlMesh& mesh);

// What every scheme evaluating these tables shares (osd-stencil, osd-glcompute): the reference
// rule, depth levels, the deviation bound of Far's patches in float, the meshes OpenSubdiv takes.
// The caller adds name, paper, description, peer, backends and parameters.
SchemeInfo limit_stencil_info(SubdivisionRule rule);
// The depths the tables are made for.
constexpr int kMaxStencilDepth = 8;

// Positions, tangents (xyz float arrays, one entry per vertex) of the vertices without a limit
// patch: refined positions, zero tangents. The limit ones are the evaluator's.
void evaluate_refined_only(const LimitStencils& s, const float* control, float* positions, float* du, float* dv);

// Scatters limit stencil results (dense, one entry per limit stencil) to their vertices.
void scatter_limit(const LimitStencils& s, const float* dense, float* out);

// The unit normal of every vertex from the tangents: du x dv, normalised in float.
void normals_from_tangents(const float* du, const float* dv, Point3* normals, size_t begin, size_t end);

}  // namespace sdb
