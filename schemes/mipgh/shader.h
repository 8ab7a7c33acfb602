// The mesh shaders (Section 5): Catmull-Clark (Figure 20 and the paper's code; Figure 21 for the
// limit) and Loop, the only scheme-specific code. The mesh processor (processor.h) hands it a node's
// 1-disk in Figure 24's enumeration (the centre, then the direct neighbours counter-clockwise,
// then the diagonal ones) and the edge tags; it returns the target node.
//
// Nodes whose 1-disk carries no tag take the paper's stencils as written (the fast paths below).
// Tagged nodes (creases, corners, global boundaries, whose edges Sdc makes infinitely sharp) take
// Pixar's rules as OpenSubdiv applies them: the masks come from Sdc::Scheme<CATMARK> fed with
// the tags, so every blend of fractional sharpness is OpenSubdiv's own.
#pragma once

#include <opensubdiv/sdc/crease.h>
#include <opensubdiv/sdc/options.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "harness/core/control_mesh.h"
#include "harness/mesh/sdc_mask.h"
#include "schemes/mipgh/mipgh.h"

namespace sdb::mipgh {

struct V3 {
  float x, y, z;
};
inline V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V3 operator*(float w, V3 a) { return {w * a.x, w * a.y, w * a.z}; }
inline V3 cross(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline V3 normalized(V3 a) {
  const float l = std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z);
  return l > 0 ? (1.0f / l) * a : a;
}

// A weighted sum of nodes in double, rounded to float once (the masks' sums: a pole's ring of 360
// terms summed in float is off by 1e-6 of the diagonal).
struct DoubleSum {
  double x = 0, y = 0, z = 0;
  void add(double w, V3 p) { x += w * p.x, y += w * p.y, z += w * p.z; }
  V3 get() const { return {float(x), float(y), float(z)}; }
};

// Figure 20, the stencils of a tag-free regular 1-disk. Templates over the point type: V3, or a
// four-float SIMD vector holding x, y, z (processor.cpp), with the same operations per coordinate.
// (The facet point, 1/4 each, is tile.cpp's quad_classes alone.)
// v0, v1 the edge's ends; f the four other corners of its two quads.
template <class P>
inline P edge_vertex(P v0, P v1, P f0, P f1, P f2, P f3) {
  return 0.375f * (v0 + v1) + 0.0625f * ((f0 + f1) + (f2 + f3));
}
// Valence 4: 36/64 centre, 6/64 direct, 1/64 diagonal neighbours.
template <class P>
inline P vertex_vertex4(P c, P e0, P e1, P e2, P e3, P d0, P d1, P d2, P d3) {
  return 0.5625f * c + 0.09375f * ((e0 + e2) + (e1 + e3)) + 0.015625f * ((d0 + d2) + (d1 + d3));
}
// Loop on a tag-free regular triangle 1-disk: the edge's ends 3/8, the two opposite corners 1/8;
// a valence-6 vertex 10/16 and 1/16 per neighbour.
template <class P>
inline P loop_edge_vertex(P v0, P v1, P o0, P o1) {
  return 0.375f * (v0 + v1) + 0.125f * (o0 + o1);
}
template <class P>
inline P loop_vertex6(P c, P e0, P e1, P e2, P e3, P e4, P e5) {
  return 0.625f * c + 0.0625f * (((e0 + e3) + (e1 + e4)) + (e2 + e5));
}

// A node's 1-disk and tags, gathered by the processor where the fast paths do not apply.
// Vertex disk: e[i] the far end of edge i (counter-clockwise), d[i] the corner of face i opposite
// the centre; face i lies between edges i and i + 1. On a global boundary edges = faces + 1.
struct VertexDisk {
  int edges = 0, faces = 0;
  V3 c{};
  std::vector<V3> e, d;
  std::vector<uint8_t> face_size;  // 4 or 3 per face (a triangle's d is the centre)
  float sharpness = 0, child_sharpness = 0;
  std::vector<float> edge_sharpness, child_edge_sharpness;
  // A D-vertex's disk: its first face is the D-facet that names the node's SurfaceCoord, so a
  // limit with a normal per side (a crease, a corner, a boundary) takes that face's (resize clears it).
  bool sided = false;
  void resize(int num_edges, int num_faces);
  bool smooth() const;  // no tag at all: the valence-n stencil of the paper's code
};

// Edge disk: the two ends, and for each of its (one or two) facets the other corners: a quad's
// two, the one next to v0 first; a triangle's one, in f[i][0].
struct EdgeDisk {
  int faces = 2;
  int face_size[2] = {4, 4};
  V3 v0{}, v1{};
  V3 f[2][2]{};
  float sharpness = 0, child_sharpness[2] = {0, 0};
};

// What the mesh processor calls for a 1-disk its fast paths do not cover.
class MeshShader {
 public:
  virtual ~MeshShader() = default;
  virtual V3 vertex_vertex(const VertexDisk& disk) const = 0;
  virtual V3 edge_vertex(const EdgeDisk& disk) const = 0;
  // Limit position and unit normal (T1 x T2) by Sdc's limit masks for the rule the tags give.
  virtual void limit(const VertexDisk& disk, V3& position, V3& normal) const = 0;
  // The masks behind the three, for a caller that applies them itself (the Vulkan passes' tables,
  // shader_table.h).
  virtual void vertex_mask(const VertexDisk& disk, SdcMask& mask) const = 0;
  virtual void edge_mask(const EdgeDisk& disk, SdcMask& mask) const = 0;
  virtual void limit_masks(const VertexDisk& disk, SdcMask& position, SdcMask& t1, SdcMask& t2) const = 0;
  // Whether vertex_mask and edge_mask give this disk's rule as Sdc masks. The quad/triangle
  // shader's rules where quads and triangles meet are not; a mask table probes those
  // (mask_table.cpp: the rules are linear in the disk's nodes).
  virtual bool has_mask(const VertexDisk&) const { return true; }
  virtual bool has_mask(const EdgeDisk&) const { return true; }
};

// Each (disk point, weight) a mask weighs, in the order the shaders sum them: the centre or the
// edge's ends, the edges' far ends, then the faces (a face centre as its corners' quarters).
template <class F>
void for_each_term(const SdcMask& m, const VertexDisk& d, F&& f) {
  f(d.c, m.VertexWeight(0));
  for (int i = 0; i < m.GetNumEdgeWeights(); ++i) f(d.e[i], m.EdgeWeight(i));
  for (int i = 0; i < m.GetNumFaceWeights(); ++i) {
    if (!m.AreFaceWeightsForFaceCenters()) {
      f(d.d[i], m.FaceWeight(i));
      continue;
    }
    const float q = 0.25f * m.FaceWeight(i);
    f(d.c, q), f(d.e[i], q), f(d.d[i], q), f(d.e[(i + 1) % d.edges], q);
  }
}

template <class F>
void for_each_term(const SdcMask& m, const EdgeDisk& d, F&& f) {
  f(d.v0, m.VertexWeight(0));
  f(d.v1, m.VertexWeight(1));
  for (int i = 0; i < m.GetNumFaceWeights(); ++i) {
    if (!m.AreFaceWeightsForFaceCenters()) {  // a triangle's opposite corner (Loop)
      f(d.f[i][0], m.FaceWeight(i));
      continue;
    }
    const float q = 0.25f * m.FaceWeight(i);
    f(d.v0, q), f(d.v1, q), f(d.f[i][0], q), f(d.f[i][1], q);
  }
}

// Sdc's masks for Catmull-Clark or Loop, fed with the 1-disk's tags; or the quad/triangle shader.
std::unique_ptr<MeshShader> make_shader(MeshRule rule, const OpenSubdiv::Sdc::Options& options);
std::unique_ptr<MeshShader> make_quad_tri_shader(const OpenSubdiv::Sdc::Options& options);  // quad_tri_shader.cpp

// The paper's extraordinary vertex-vertex stencil (Section 5's code), any valence, no tags.
V3 catmark_vertex_smooth(const VertexDisk& disk);

// Limit projection of a tag-free regular node: Catmull-Clark's (16, 4, 1)/36 and Figure 21's
// derivative stencils; Loop's 1/2 and 1/12 per neighbour and its regular tangent masks.
inline V3 catmark_limit_position(V3 c, const V3 e[4], const V3 d[4]) {
  return (1.0f / 36) * (16.0f * c + 4.0f * ((e[0] + e[2]) + (e[1] + e[3])) + ((d[0] + d[2]) + (d[1] + d[3])));
}
inline void catmark_limit_regular(V3 c, const V3 e[4], const V3 d[4], V3& position, V3& normal) {
  position = catmark_limit_position(c, e, d);
  // Figure 21: T1 towards e0, T2 towards e1; d[i] lies between e[i] and e[i + 1].
  const V3 t1 = 4.0f * (e[0] - e[2]) + ((d[0] + d[3]) - (d[1] + d[2]));
  const V3 t2 = 4.0f * (e[1] - e[3]) + ((d[0] + d[1]) - (d[2] + d[3]));
  normal = normalized(cross(t1, t2));
}

inline void loop_limit_regular(V3 c, const V3 e[6], V3& position, V3& normal) {
  position = 0.5f * c + (1.0f / 12) * (((e[0] + e[3]) + (e[1] + e[4])) + (e[2] + e[5]));
  // Sdc's valence-6 tangents: cos and sin of 60-degree steps (the sqrt(3)/2 factor cancels).
  const V3 t1 = (e[0] - e[3]) + 0.5f * ((e[1] - e[2]) - (e[4] - e[5]));
  const V3 t2 = (e[1] + e[2]) - (e[4] + e[5]);
  normal = normalized(cross(t1, t2));
}

}  // namespace sdb::mipgh
