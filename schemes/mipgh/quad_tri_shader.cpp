// The quad/triangle mesh shader (Stam and Loop 2003, the paper's reference 19): Catmull-Clark
// where a 1-disk holds quads only, Loop where it holds triangles only (Sdc's masks, creases
// included), and where quads and triangles meet, Stam and Loop's averaging: after the linear split
// (edge midpoints, quad centroids, triangles in four) a node moves to v + a (c - v), c the average
// of its new faces' points weighted by their regular angles (a quad pi/2 with its centroid, a
// triangle pi/3 with 1/4 v + 3/8 each other corner), a = 12 / (3 n_q + 2 n_t). On quads only it
// is Catmull-Clark, on triangles only (with Loop's a) Loop, at every level (README.md says where
// the rules come from). Creases through mixed 1-disks take the crease and corner masks, which the
// two schemes share, blended by Sdc's fractional weight as Sdc blends them.
#include <opensubdiv/sdc/crease.h>

#include <stdexcept>

#include "schemes/mipgh/shader.h"

namespace sdb::mipgh {
namespace {

namespace Sdc = OpenSubdiv::Sdc;

// Stam and Loop's smooth rule at a vertex whose faces mix quads and triangles (no boundary).
V3 mixed_smooth_vertex(const VertexDisk& d) {
  int quads = 0;
  for (int i = 0; i < d.faces; ++i) quads += d.face_size[i] == 4;
  const int triangles = d.faces - quads;
  // Angles in units of pi/6: a quad 3, a triangle 2; their sum W = 3 n_q + 2 n_t (12 when regular).
  const double W = 3.0 * quads + 2.0 * triangles, a = 12.0 / W;
  // c = sum over faces of angle * point / W, each point written in the disk's nodes
  DoubleSum c;
  for (int i = 0; i < d.faces; ++i) {
    const V3 ei = d.e[i], ej = d.e[(i + 1) % d.edges];
    if (d.face_size[i] == 4) {
      // the sub-quad (v, mid_i, centroid, mid_j): 1/4 each; mid = (v + e) / 2, centroid = (v + e_i + d + e_j) / 4
      const double w = 3.0 / W;
      c.add(w * (0.25 + 0.125 + 0.0625 + 0.125), d.c);
      c.add(w * (0.125 + 0.0625), ei), c.add(w * (0.125 + 0.0625), ej);
      c.add(w * 0.0625, d.d[i]);
    } else {
      // the corner triangle (v, mid_i, mid_j): 1/4 v + 3/8 mid_i + 3/8 mid_j
      const double w = 2.0 / W;
      c.add(w * (0.25 + 0.375), d.c);
      c.add(w * 0.1875, ei), c.add(w * 0.1875, ej);
    }
  }
  const V3 avg = c.get();
  DoubleSum r;
  r.add(1.0 - a, d.c), r.add(a, avg);
  return r.get();
}

// A crease (3/4, 1/8, 1/8 along its two sharp edges) or a corner, by the sharpness given.
V3 sharp_vertex(const VertexDisk& d, Sdc::Crease::Rule rule, const float* edge_sharpness) {
  if (rule == Sdc::Crease::RULE_CORNER) return d.c;
  DoubleSum r;
  r.add(0.75, d.c);
  for (int i = 0; i < d.edges; ++i)
    if (edge_sharpness[i] > 0) r.add(0.125, d.e[i]);
  return r.get();
}

class QuadTriShader final : public MeshShader {
 public:
  explicit QuadTriShader(const Sdc::Options& options)
      : options_(options),
        catmark_(make_shader(MeshRule::CatmullClark, options)),
        loop_(make_shader(MeshRule::Loop, options)) {}

  V3 vertex_vertex(const VertexDisk& d) const override {
    if (const MeshShader* pure = pure_shader(d)) return pure->vertex_vertex(d);
    const Sdc::Crease crease(options_);
    const auto parent = crease.DetermineVertexVertexRule(d.sharpness, d.edges, d.edge_sharpness.data());
    if (parent == Sdc::Crease::RULE_SMOOTH || parent == Sdc::Crease::RULE_DART) return mixed_smooth_vertex(d);
    const V3 sharp = sharp_vertex(d, parent, d.edge_sharpness.data());
    const auto child = crease.DetermineVertexVertexRule(d.child_sharpness, d.edges, d.child_edge_sharpness.data());
    if (child == parent) return sharp;
    const double w = crease.ComputeFractionalWeightAtVertex(d.sharpness, d.child_sharpness, d.edges,
                                                            d.edge_sharpness.data(), d.child_edge_sharpness.data());
    const V3 other = child == Sdc::Crease::RULE_SMOOTH || child == Sdc::Crease::RULE_DART
                         ? mixed_smooth_vertex(d)
                         : sharp_vertex(d, child, d.child_edge_sharpness.data());
    DoubleSum r;
    r.add(w, sharp), r.add(1.0 - w, other);
    return r.get();
  }

  V3 edge_vertex(const EdgeDisk& d) const override {
    if (const MeshShader* pure = pure_shader(d)) return pure->edge_vertex(d);
    // A quad on one side, a triangle on the other (derived from the averaging: the new node has
    // two quads and three triangles around it, a = 1): 3/8 each end, 1/16 each of the quad's far
    // corners, 1/8 the triangle's.
    const int q = d.face_size[0] == 4 ? 0 : 1;
    DoubleSum smooth;
    smooth.add(0.375, d.v0), smooth.add(0.375, d.v1);
    smooth.add(0.0625, d.f[q][0]), smooth.add(0.0625, d.f[q][1]), smooth.add(0.125, d.f[1 - q][0]);
    if (d.sharpness <= 0) return smooth.get();
    DoubleSum mid;
    mid.add(0.5, d.v0), mid.add(0.5, d.v1);
    if (d.child_sharpness[0] > 0 || d.child_sharpness[1] > 0) return mid.get();
    // Sdc's blend where a semi-sharp edge ends: its sharpness weighs the crease's midpoint
    const double w = d.sharpness < 1 ? d.sharpness : 1.0;
    DoubleSum r;
    r.add(w, mid.get()), r.add(1.0 - w, smooth.get());
    return r.get();
  }

  void limit(const VertexDisk& d, V3& position, V3& normal) const override {
    if (const MeshShader* pure = pure_shader(d)) return pure->limit(d, position, normal);
    throw std::logic_error("the quad/triangle shader has no limit masks where quads and triangles meet");
  }
  void vertex_mask(const VertexDisk& d, SdcMask& m) const override {
    if (const MeshShader* pure = pure_shader(d)) return pure->vertex_mask(d, m);
    throw std::logic_error("the quad/triangle shader's mixed rules are not Sdc masks");
  }
  void edge_mask(const EdgeDisk& d, SdcMask& m) const override {
    if (const MeshShader* pure = pure_shader(d)) return pure->edge_mask(d, m);
    throw std::logic_error("the quad/triangle shader's mixed rules are not Sdc masks");
  }
  bool has_mask(const VertexDisk& d) const override { return pure_shader(d) != nullptr; }
  bool has_mask(const EdgeDisk& d) const override { return pure_shader(d) != nullptr; }
  void limit_masks(const VertexDisk& d, SdcMask& p, SdcMask& t1, SdcMask& t2) const override {
    if (const MeshShader* pure = pure_shader(d)) return pure->limit_masks(d, p, t1, t2);
    throw std::logic_error("the quad/triangle shader has no limit masks where quads and triangles meet");
  }

 private:
  // Catmull-Clark's shader for a disk of quads only, Loop's for triangles only, else none.
  const MeshShader* pure_shader(const VertexDisk& d) const {
    int quads = 0;
    for (int i = 0; i < d.faces; ++i) quads += d.face_size[i] == 4;
    if (quads == d.faces) return catmark_.get();
    if (quads == 0) return loop_.get();
    return nullptr;
  }
  // The same for an edge: its one facet's kind, or its two facets' where they are of one kind.
  const MeshShader* pure_shader(const EdgeDisk& d) const {
    if (d.faces == 2 && d.face_size[0] != d.face_size[1]) return nullptr;
    return d.face_size[0] == 4 ? catmark_.get() : loop_.get();
  }

  Sdc::Options options_;
  std::unique_ptr<MeshShader> catmark_, loop_;
};

}  // namespace

std::unique_ptr<MeshShader> make_quad_tri_shader(const Sdc::Options& options) {
  return std::make_unique<QuadTriShader>(options);
}

}  // namespace sdb::mipgh
