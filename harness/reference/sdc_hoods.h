// The neighbourhoods Sdc's mask queries read (a ring's subdivision matrix, ring_limit.h; the fragments'
// tables), on Far's public TopologyLevel: what Far's own
// Vtr::internal::EdgeInterface and VertexInterface give PrimvarRefiner, so the masks are its.
#pragma once

#include <opensubdiv/far/topologyLevel.h>
#include <opensubdiv/sdc/crease.h>

#include <vector>

#include "harness/mesh/sdc_mask.h"

namespace sdb {

namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;

class EdgeHood {
 public:
  EdgeHood(const Far::TopologyLevel& level, int edge) : level_(level), edge_(edge) {}
  int GetNumFaces() const { return level_.GetEdgeFaces(edge_).size(); }
  float GetSharpness() const { return level_.GetEdgeSharpness(edge_); }
  void GetChildSharpnesses(const Sdc::Crease&, float s[2]) const { s[0] = s[1] = GetSharpness() - 1.0f; }
  void GetNumVerticesPerFace(int counts[]) const {
    Far::ConstIndexArray faces = level_.GetEdgeFaces(edge_);
    for (int i = 0; i < faces.size(); ++i) counts[i] = level_.GetFaceVertices(faces[i]).size();
  }

 private:
  const Far::TopologyLevel& level_;
  int edge_;
};

class VertexHood {
 public:
  // `start` rotates the ring (interior vertices only): Sdc reads edge and face i as Far's i + start.
  VertexHood(const Far::TopologyLevel& parent, const Far::TopologyLevel& child, int vertex, int child_vertex,
             int start = 0)
      : parent_(parent), child_(child), vertex_(vertex), child_vertex_(child_vertex), start_(start) {}
  int GetNumEdges() const { return parent_.GetVertexEdges(vertex_).size(); }
  int GetNumFaces() const { return parent_.GetVertexFaces(vertex_).size(); }
  float GetSharpness() const { return parent_.GetVertexSharpness(vertex_); }
  float* GetSharpnessPerEdge(float s[]) const {
    Far::ConstIndexArray edges = parent_.GetVertexEdges(vertex_);
    for (int i = 0; i < edges.size(); ++i) s[i] = parent_.GetEdgeSharpness(edges[(i + start_) % edges.size()]);
    return s;
  }
  float GetChildSharpness(const Sdc::Crease&) const { return child_.GetVertexSharpness(child_vertex_); }
  float* GetChildSharpnessPerEdge(const Sdc::Crease& crease, float s[]) const {
    std::vector<float> p(GetNumEdges());
    GetSharpnessPerEdge(p.data());
    crease.SubdivideEdgeSharpnessesAroundVertex(GetNumEdges(), p.data(), s);
    return s;
  }

 private:
  const Far::TopologyLevel &parent_, &child_;
  int vertex_, child_vertex_, start_;
};

}  // namespace sdb
