#include "harness/reference/local_mesh.h"

#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>

#include <algorithm>
#include <set>
#include <stdexcept>

namespace sdb {
namespace {

namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;

// A point as PrimvarRefinerReal<double> interpolates it: double weights on double coordinates.
struct DoublePoint {
  double p[3];
  void Clear(void* = nullptr) { p[0] = p[1] = p[2] = 0; }
  void AddWithWeight(const DoublePoint& s, double w) {
    p[0] += w * s.p[0];
    p[1] += w * s.p[1];
    p[2] += w * s.p[2];
  }
};

}  // namespace

LocalMesh cut_faces(const Far::TopologyLevel& l, const std::vector<Point3d>& points, const std::vector<int>& faces,
                    std::vector<int>* local_of, const std::vector<char>* marks) {
  LocalMesh m;
  std::vector<int> local(l.GetNumVertices(), -1);
  auto index = [&](int u) {
    if (local[u] < 0) {
      local[u] = static_cast<int>(m.points.size());
      m.points.push_back(points[u]);
      m.marks.push_back(marks ? (*marks)[u] : 0);
      if (const float s = l.GetVertexSharpness(u); s > 0) m.corner_vertices.push_back(local[u]), m.corner_weights.push_back(s);
    }
    return local[u];
  };
  std::set<int> edges;
  for (size_t k = 0; k < faces.size(); ++k) {
    Far::ConstIndexArray fv = l.GetFaceVertices(faces[k]), fe = l.GetFaceEdges(faces[k]);
    m.face_sizes.push_back(fv.size());
    for (int u : fv) m.face_vertices.push_back(index(u));
    for (int e : fe) edges.insert(e);
    if (l.IsFaceHole(faces[k])) m.holes.push_back(static_cast<int>(k));
  }
  for (int e : edges) {
    const float s = l.GetEdgeSharpness(e);
    if (s <= 0) continue;
    Far::ConstIndexArray ends = l.GetEdgeVertices(e);
    m.crease_pairs.push_back(local[ends[0]]);
    m.crease_pairs.push_back(local[ends[1]]);
    m.crease_weights.push_back(s);
  }
  if (local_of) *local_of = std::move(local);
  return m;
}

std::vector<char> refine_marks(const Far::TopologyRefiner& r, const std::vector<char>& marks) {
  const Far::TopologyLevel &p = r.GetLevel(0), &c = r.GetLevel(1);
  std::vector<char> out(c.GetNumVertices(), 0);
  for (int v = 0; v < p.GetNumVertices(); ++v)
    if (marks[v] && p.GetVertexChildVertex(v) >= 0) out[p.GetVertexChildVertex(v)] = 1;
  for (int e = 0; e < p.GetNumEdges(); ++e) {
    Far::ConstIndexArray ends = p.GetEdgeVertices(e);
    if (marks[ends[0]] && marks[ends[1]] && p.GetEdgeChildVertex(e) >= 0) out[p.GetEdgeChildVertex(e)] = 1;
  }
  return out;
}

LocalMesh ring_mesh(int edges, int faces, const std::vector<float>& edge_sharpness, float vertex_sharpness,
                    bool catmark) {
  LocalMesh m;
  m.points.assign(1 + edges + (catmark ? faces : 0), Point3d{0, 0, 0});
  for (int i = 0; i < faces; ++i) {
    const int a = 1 + i, b = 1 + (i + 1) % edges;
    if (catmark) m.face_sizes.push_back(4), m.face_vertices.insert(m.face_vertices.end(), {0, a, 1 + edges + i, b});
    else m.face_sizes.push_back(3), m.face_vertices.insert(m.face_vertices.end(), {0, a, b});
  }
  for (int i = 0; i < edges; ++i)
    if (edge_sharpness[i] > 0.0f)
      m.crease_pairs.insert(m.crease_pairs.end(), {0, 1 + i}), m.crease_weights.push_back(edge_sharpness[i]);
  if (vertex_sharpness > 0.0f) m.corner_vertices.push_back(0), m.corner_weights.push_back(vertex_sharpness);
  return m;
}

std::vector<int> faces_around(const Far::TopologyLevel& l, int f) {
  std::vector<int> out = {f};
  for (int v : l.GetFaceVertices(f))
    for (int g : l.GetVertexFaces(v))
      if (std::find(out.begin(), out.end(), g) == out.end()) out.push_back(g);
  return out;
}

std::unique_ptr<Far::TopologyRefiner> refiner_of(const LocalMesh& m, SubdivisionRule rule, const Sdc::Options& options) {
  Far::TopologyDescriptor d;
  d.numVertices = static_cast<int>(m.points.size());
  d.numFaces = static_cast<int>(m.face_sizes.size());
  d.numVertsPerFace = m.face_sizes.data();
  d.vertIndicesPerFace = m.face_vertices.data();
  d.numCreases = static_cast<int>(m.crease_weights.size());
  d.creaseVertexIndexPairs = m.crease_pairs.data();
  d.creaseWeights = m.crease_weights.data();
  d.numCorners = static_cast<int>(m.corner_weights.size());
  d.cornerVertexIndices = m.corner_vertices.data();
  d.cornerWeights = m.corner_weights.data();
  d.numHoles = static_cast<int>(m.holes.size());
  d.holeIndices = m.holes.data();
  using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
  const Sdc::SchemeType type = rule == SubdivisionRule::Loop ? Sdc::SCHEME_LOOP : Sdc::SCHEME_CATMARK;
  std::unique_ptr<Far::TopologyRefiner> r(Factory::Create(d, Factory::Options(type, options)));
  if (!r) throw std::logic_error("local refinement: Far refuses a cut-out of a mesh it took");
  return r;
}

std::vector<Point3d> refine_once(Far::TopologyRefiner& r, const std::vector<Point3d>& points) {
  Far::TopologyRefiner::UniformOptions uniform(1);
  uniform.fullTopologyInLastLevel = true;
  r.RefineUniform(uniform);
  std::vector<DoublePoint> src(points.size()), dst(r.GetLevel(1).GetNumVertices());
  for (size_t i = 0; i < points.size(); ++i) src[i] = {{points[i][0], points[i][1], points[i][2]}};
  DoublePoint* out = dst.data();
  Far::PrimvarRefinerReal<double>(r).Interpolate(1, src.data(), out);
  std::vector<Point3d> next(dst.size());
  for (size_t i = 0; i < dst.size(); ++i) next[i] = {dst[i].p[0], dst[i].p[1], dst[i].p[2]};
  return next;
}

}  // namespace sdb
