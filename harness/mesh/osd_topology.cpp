#include "harness/mesh/osd_topology.h"

#include <opensubdiv/far/error.h>
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <vector>

#include "harness/core/errors.h"

namespace sdb {
namespace {

namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;

// OpenSubdiv reports through a process-wide callback; collect the first message of a call.
std::mutex g_error_mutex;
std::string g_last_error;

void capture_error(Far::ErrorType, const char* message) {
  if (g_last_error.empty()) g_last_error = message;
}

}  // namespace

Sdc::Options sdc_options(const ControlMesh& m) {
  Sdc::Options o;
  switch (m.boundary) {
    case BoundaryRule::None: o.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_NONE); break;
    case BoundaryRule::EdgeOnly: o.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_ONLY); break;
    case BoundaryRule::EdgeAndCorner: o.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER); break;
  }
  o.SetCreasingMethod(m.crease_method == CreaseMethod::Chaikin ? Sdc::Options::CREASE_CHAIKIN
                                                               : Sdc::Options::CREASE_UNIFORM);
  o.SetTriangleSubdivision(m.triangle_rule == TriangleRule::Smooth ? Sdc::Options::TRI_SUB_SMOOTH
                                                                   : Sdc::Options::TRI_SUB_CATMARK);
  return o;
}

std::unique_ptr<Far::TopologyRefiner> make_refiner(const ControlMesh& m, SubdivisionRule rule) {
  std::vector<int> crease_pairs;
  std::vector<float> crease_weights;
  for (const auto& c : m.creases) {
    crease_pairs.push_back(c.v0);
    crease_pairs.push_back(c.v1);
    crease_weights.push_back(c.sharpness);
  }
  std::vector<int> corner_vertices;
  std::vector<float> corner_weights;
  for (const auto& c : m.corners) {
    corner_vertices.push_back(c.vertex);
    corner_weights.push_back(c.sharpness);
  }
  Far::TopologyDescriptor desc;
  desc.numVertices = num_vertices(m);
  desc.numFaces = num_faces(m);
  desc.numVertsPerFace = m.face_sizes.data();
  desc.vertIndicesPerFace = m.face_vertices.data();
  desc.numCreases = static_cast<int>(m.creases.size());
  desc.creaseVertexIndexPairs = crease_pairs.data();
  desc.creaseWeights = crease_weights.data();
  desc.numCorners = static_cast<int>(m.corners.size());
  desc.cornerVertexIndices = corner_vertices.data();
  desc.cornerWeights = corner_weights.data();
  desc.numHoles = static_cast<int>(m.holes.size());
  desc.holeIndices = m.holes.data();

  using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
  const Sdc::SchemeType type = rule == SubdivisionRule::Loop ? Sdc::SCHEME_LOOP : Sdc::SCHEME_CATMARK;
  std::lock_guard<std::mutex> lock(g_error_mutex);
  g_last_error.clear();
  Far::SetErrorCallback(capture_error);
  std::unique_ptr<Far::TopologyRefiner> refiner(Factory::Create(desc, Factory::Options(type, sdc_options(m))));
  Far::SetErrorCallback(nullptr);
  if (!refiner) throw InputError(m.source, "OpenSubdiv refuses the topology: " + g_last_error);
  return refiner;
}

ControlMesh refined_level(const Far::TopologyRefiner& refiner, const ControlMesh& base, int level) {
  if (level > refiner.GetMaxLevel()) throw std::logic_error("refined_level: refiner not refined that far");
  // Without it Far leaves the last level's edges unbuilt, and reading their sharpness reads garbage.
  if (level == refiner.GetMaxLevel() && !refiner.IsUniform()) throw std::logic_error("refined_level: adaptive refiner");
  if (level == refiner.GetMaxLevel() && !refiner.GetUniformOptions().fullTopologyInLastLevel)
    throw std::logic_error("refined_level: refine with UniformOptions::fullTopologyInLastLevel");
  std::vector<PrimvarPoint> verts(refiner.GetNumVerticesTotal());
  for (int v = 0; v < num_vertices(base); ++v)
    for (int k = 0; k < 3; ++k) verts[v].p[k] = base.positions[v][k];
  Far::PrimvarRefiner primvar(refiner);
  PrimvarPoint* src = verts.data();
  for (int l = 1; l <= level; ++l) {
    PrimvarPoint* dst = src + refiner.GetLevel(l - 1).GetNumVertices();
    primvar.Interpolate(l, src, dst);
    src = dst;
  }
  const Far::TopologyLevel& lv = refiner.GetLevel(level);
  ControlMesh out;
  out.name = base.name;
  out.source = base.source;
  out.boundary = base.boundary;
  out.crease_method = base.crease_method;
  out.triangle_rule = base.triangle_rule;
  out.warnings = base.warnings;
  out.positions.resize(lv.GetNumVertices());
  for (int v = 0; v < lv.GetNumVertices(); ++v) out.positions[v] = {src[v].p[0], src[v].p[1], src[v].p[2]};
  for (int f = 0; f < lv.GetNumFaces(); ++f) {
    Far::ConstIndexArray fv = lv.GetFaceVertices(f);
    out.face_sizes.push_back(fv.size());
    for (int k = 0; k < fv.size(); ++k) out.face_vertices.push_back(fv[k]);
    if (lv.IsFaceHole(f)) out.holes.push_back(f);
    if (!base.face_lines.empty()) {
      int parent = f;  // walk back to the base face for its source line
      for (int l = level; l > 0; --l) parent = refiner.GetLevel(l).GetFaceParentFace(parent);
      out.face_lines.push_back(base.face_lines[parent]);
    }
  }
  for (int e = 0; e < lv.GetNumEdges(); ++e) {
    const float s = lv.GetEdgeSharpness(e);
    if (s > 0.0f) out.creases.push_back({lv.GetEdgeVertices(e)[0], lv.GetEdgeVertices(e)[1], s});
  }
  for (int v = 0; v < lv.GetNumVertices(); ++v) {
    const float s = lv.GetVertexSharpness(v);
    if (s > 0.0f) out.corners.push_back({v, s});
  }
  return out;
}

bool far_tangent_masks_exact(const Far::TopologyLevel& l, int v, SubdivisionRule rule, bool infinite_only) {
  Far::ConstIndexArray ve = l.GetVertexEdges(v);
  const int faces = l.GetVertexFaces(v).size(), edges = ve.size(), side = rule == SubdivisionRule::Loop ? 3 : 2;
  std::vector<int> sharp;
  for (int i = 0; i < edges; ++i)
    if (infinite_only ? l.IsEdgeInfSharp(ve[i]) : l.GetEdgeSharpness(ve[i]) > 0) sharp.push_back(i);
  const bool corner = infinite_only ? l.IsVertexInfSharp(v) : l.GetVertexSharpness(v) > 0;
  if (corner || sharp.size() > 2) return l.IsVertexBoundary(v) && faces == 1;
  if (sharp.size() == 2) return l.IsVertexBoundary(v) ? faces == side : faces == 2 * side && sharp[1] - sharp[0] == side;
  return sharp.empty() && edges >= 3;  // smooth; a dart (one sharp edge) is not
}

namespace {

float finite_sharpness(const ControlMesh& mesh) {
  float s = 0;
  for (const EdgeCrease& c : mesh.creases)
    if (c.sharpness < 10) s = std::max(s, c.sharpness);  // Far's infinitely sharp is 10
  for (const VertexCorner& c : mesh.corners)
    if (c.sharpness < 10) s = std::max(s, c.sharpness);
  return s;
}

}  // namespace

int limit_depth_for(const ControlMesh& mesh, int depth) {
  return std::max(depth, static_cast<int>(std::ceil(finite_sharpness(mesh))));
}

std::optional<std::string> limit_depth_refusal(const ControlMesh& mesh, int depth, double faces, double budget) {
  const int level = limit_depth_for(mesh, depth);
  if (level == depth || faces * std::ldexp(1.0, 2 * level) <= budget) return std::nullopt;
  char why[240];
  std::snprintf(why, sizeof why,
                "semi-sharp creases of sharpness %.3g outlast depth %d: the exact limit is projected from level %d, "
                "%.3g faces, past this scheme's %.3g",
                finite_sharpness(mesh), depth, level, faces * std::ldexp(1.0, 2 * level), budget);
  return mesh.source + ": " + why;
}

}  // namespace sdb
