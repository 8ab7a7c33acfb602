#include "schemes/mipgh/facet_masks.h"

#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>

#include <array>
#include <cmath>
#include <map>

#include "harness/mesh/osd_topology.h"
#include "schemes/mipgh/regular_patches.h"
#include "schemes/mipgh/tile.h"

namespace sdb::mipgh {
namespace {

using namespace OpenSubdiv;

// A 1-ring this large or larger keeps the level's own masks (valences past 20 around the facet).
constexpr int kMaxRing = 64;

// One refined vertex as weights on the 1-ring's control points: Far's primvar interface.
struct Weights {
  std::array<double, kMaxRing> w;
  void Clear(void* = nullptr) { w.fill(0.0); }
  void AddWithWeight(const Weights& s, double weight) {
    for (int k = 0; k < kMaxRing; ++k) w[size_t(k)] += weight * s.w[size_t(k)];
  }
};

// D-facet f's 1-ring (every face at its corners, f first, each from the corner it is met at, its
// control points numbered as met, f's corner 0 first) when it is untagged, interior and all quads.
struct Ring {
  std::vector<int32_t> vertices;     // global, by local number
  std::vector<int32_t> face_vertices;  // local, four per face
};
bool ring_of(const DAtlas& atlas, const EdgeTags& tags, int f, Ring& out) {
  if (atlas.facet_size[f] != 4) return false;
  out.vertices.clear(), out.face_vertices.clear();
  std::map<int32_t, int32_t> local;
  std::vector<int32_t> faces;
  auto number = [&](int32_t v) {
    auto [it, fresh] = local.try_emplace(v, int32_t(out.vertices.size()));
    if (fresh) out.vertices.push_back(v);
    return it->second;
  };
  for (int k = 0; k < 4; ++k) {
    const int v = atlas.facet_corners[f][k];
    if (atlas.valence(v) == 0 || atlas.vertex_boundary[v] || atlas.vertex_fans[v] != 1) return false;
    const int begin = atlas.ring_offsets[v], valence = atlas.valence(v);
    int r = 0;
    while (r < valence && atlas.ring[begin + r].facet != f) ++r;
    if (r == valence) return false;
    for (int i = 0; i < valence; ++i) {
      const HalfEdge& h = atlas.ring[begin + (r + i) % valence];
      if (atlas.facet_size[h.facet] != 4) return false;
      bool seen = false;
      for (int32_t g : faces) seen |= g == h.facet;
      if (seen) continue;
      faces.push_back(h.facet);
      for (int t = 0; t < 4; ++t) {
        if (tags.any && tags.slot[atlas.facet_edges[h.facet][(h.side + t) & 3]] >= 0) return false;
        out.face_vertices.push_back(number(atlas.facet_corners[h.facet][(h.side + t) & 3]));
      }
    }
  }
  if (int(out.vertices.size()) > kMaxRing) return false;
  if (tags.any)
    for (int32_t v : out.vertices)
      if (tags.vertex[0][v] != 0.0f) return false;
  return true;
}

// The weights of the limit tangents at every grid node of local face 0 at level sigma.
std::vector<float> compose(const Ring& ring, const Sdc::Options& options, int sigma) {
  const int size = int(ring.vertices.size()), faces = int(ring.face_vertices.size() / 4);
  std::vector<int> per_face(faces, 4);
  Far::TopologyDescriptor desc;
  desc.numVertices = size, desc.numFaces = faces;
  desc.numVertsPerFace = per_face.data(), desc.vertIndicesPerFace = ring.face_vertices.data();
  using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
  std::unique_ptr<Far::TopologyRefiner> refiner(
      Factory::Create(desc, Factory::Options(Sdc::SCHEME_CATMARK, options)));
  Far::TopologyRefiner::UniformOptions uniform(sigma);
  uniform.fullTopologyInLastLevel = true;
  refiner->RefineUniform(uniform);
  // One-hot control points, refined to sigma in double.
  std::vector<Weights> level(static_cast<size_t>(size));
  for (int k = 0; k < size; ++k) level[size_t(k)].Clear(), level[size_t(k)].w[size_t(k)] = 1.0;
  Far::PrimvarRefinerReal<double> primvars(*refiner);
  for (int l = 1; l <= sigma; ++l) {
    std::vector<Weights> next(size_t(refiner->GetLevel(l).GetNumVertices()));
    Weights *src = level.data(), *dst = next.data();
    primvars.Interpolate(l, src, dst);
    level.swap(next);
  }
  std::vector<Weights> position(level.size()), t1(level.size()), t2(level.size());
  Weights *last = level.data(), *limit = position.data(), *du = t1.data(), *dv = t2.data();
  primvars.Limit(last, limit, du, dv);
  // Local face 0's grid: each face's corners as (row, column) of the level's grid, followed down.
  const int N = 1 << sigma, n = N + 1;
  struct Tracked {
    int face;
    std::array<int, 2> corner[4];
  };
  std::vector<Tracked> tracked(1);
  tracked[0].face = 0;
  tracked[0].corner[0] = {0, 0}, tracked[0].corner[1] = {0, N}, tracked[0].corner[2] = {N, N}, tracked[0].corner[3] = {N, 0};
  for (int l = 0; l < sigma; ++l) {
    const Far::TopologyLevel &parent = refiner->GetLevel(l), &child = refiner->GetLevel(l + 1);
    std::vector<Tracked> next;
    for (const Tracked& p : tracked) {
      const auto pv = parent.GetFaceVertices(p.face);
      const auto pe = parent.GetFaceEdges(p.face);
      auto position_of = [&](int x) -> std::array<int, 2> {
        for (int k = 0; k < 4; ++k) {
          if (x == parent.GetVertexChildVertex(pv[k])) return p.corner[k];
          if (x == parent.GetEdgeChildVertex(pe[k])) {
            const auto ev = parent.GetEdgeVertices(pe[k]);
            std::array<int, 2> a{}, b{};
            for (int c = 0; c < 4; ++c) {
              if (pv[c] == ev[0]) a = p.corner[c];
              if (pv[c] == ev[1]) b = p.corner[c];
            }
            return {(a[0] + b[0]) / 2, (a[1] + b[1]) / 2};
          }
        }
        return {(p.corner[0][0] + p.corner[2][0]) / 2, (p.corner[0][1] + p.corner[2][1]) / 2};  // the face point
      };
      for (int c : parent.GetFaceChildFaces(p.face)) {
        Tracked t{c, {}};
        const auto cv = child.GetFaceVertices(c);
        for (int k = 0; k < 4; ++k) t.corner[k] = position_of(cv[k]);
        next.push_back(t);
      }
    }
    tracked.swap(next);
  }
  std::vector<float> weights(size_t(n) * size_t(n) * 2 * size_t(size), 0.0f);
  for (const Tracked& t : tracked) {
    const auto v = refiner->GetLevel(sigma).GetFaceVertices(t.face);
    for (int k = 0; k < 4; ++k) {
      float* w = &weights[(size_t(t.corner[k][0]) * n + size_t(t.corner[k][1])) * 2 * size_t(size)];
      for (int c = 0; c < size; ++c) w[c] = float(t1[size_t(v[k])].w[size_t(c)]), w[size + c] = float(t2[size_t(v[k])].w[size_t(c)]);
    }
  }
  return weights;
}

thread_local std::vector<V3> t_differences;

// Type::by_point's layout of level sigma's node weights `w` (the interior, then the sides).
void lay_out_by_point(const std::vector<float>& w, int size, int sigma, std::vector<float>& out, size_t& pitch) {
  const int n = (1 << sigma) + 1, inner = n - 2;
  std::vector<RowColumn> nodes;
  for (int i = 1; i + 1 < n; ++i)
    for (int j = 1; j + 1 < n; ++j) nodes.push_back({i, j});
  for (int side = 0; side < 4; ++side)
    for (int a = 1; a <= inner; ++a) nodes.push_back(side_ij(4, side, n, a, 0));
  pitch = (nodes.size() + 7 + 7) & ~size_t(7);  // tile::weighted_normals reads up to 8 past a run
  out.assign(2 * size_t(size - 1) * pitch, 0.0f);
  for (size_t k = 0; k < nodes.size(); ++k) {
    const float* node = &w[(size_t(nodes[k].i) * n + size_t(nodes[k].j)) * 2 * size_t(size)];
    for (int c = 1; c < size; ++c) {
      out[2 * size_t(c - 1) * pitch + k] = node[c];
      out[(2 * size_t(c - 1) + 1) * pitch + k] = node[size + c];
    }
  }
}

}  // namespace

FacetMasks compose_facet_masks(const ControlMesh& mesh, const DAtlas& atlas, const EdgeTags& tags,
                               const RegularPatches& regular, int depth) {
  FacetMasks out;
  out.facet.assign(atlas.num_facets(), -1);
  if (depth < 1) return out;
  const Sdc::Options options = sdc_options(mesh);
  std::map<std::vector<int32_t>, uint32_t> type_of;
  Ring ring;
  for (int f = 0; f < atlas.num_facets(); ++f) {
    if (regular.regular(f) || !ring_of(atlas, tags, f, ring)) continue;
    auto [it, fresh] = type_of.try_emplace(ring.face_vertices, uint32_t(out.types.size()));
    if (fresh) {
      FacetMasks::Type t;
      t.size = int(ring.vertices.size());
      t.weights.resize(size_t(depth) + 1);
      t.by_point.resize(size_t(depth) + 1), t.pitch.assign(size_t(depth) + 1, 0);
      for (int sigma = 1; sigma <= depth; ++sigma) {
        t.weights[size_t(sigma)] = compose(ring, options, sigma);
        lay_out_by_point(t.weights[size_t(sigma)], t.size, sigma, t.by_point[size_t(sigma)], t.pitch[size_t(sigma)]);
      }
      out.types.push_back(std::move(t));
    }
    out.facet[size_t(f)] = int32_t(out.facets.size());
    out.facets.push_back({it->second, uint32_t(out.control.size())});
    out.control.insert(out.control.end(), ring.vertices.begin(), ring.vertices.end());
  }
  return out;
}

namespace {

// The 1-ring's differences from its first control point (f's corner 0) into t_differences.
const V3* differences(const FacetMasks& m, const FacetMasks::Facet& f, int size, const V3* base) {
  t_differences.resize(size_t(size));
  const uint32_t* control = &m.control[f.first];
  const V3 c = base[control[0]];
  for (int k = 0; k < size; ++k) t_differences[size_t(k)] = base[control[k]] - c;
  return t_differences.data();
}

}  // namespace

void FacetMasks::interior_normals(int f, int sigma, const V3* base, V3* out) const {
  const Facet& facet_ = facets[size_t(facet[size_t(f)])];
  const Type& t = types[facet_.type];
  const int inner = (1 << sigma) - 1;
  tile::weighted_normals(t.by_point[size_t(sigma)].data(), t.pitch[size_t(sigma)],
                         differences(*this, facet_, t.size, base) + 1, t.size - 1, inner * inner, out);
}

void FacetMasks::side_normals(int f, int sigma, int side, const V3* base, V3* out) const {
  const Facet& facet_ = facets[size_t(facet[size_t(f)])];
  const Type& t = types[facet_.type];
  const int inner = (1 << sigma) - 1;
  tile::weighted_normals(t.by_point[size_t(sigma)].data() + size_t(inner) * size_t(inner + side),
                         t.pitch[size_t(sigma)], differences(*this, facet_, t.size, base) + 1, t.size - 1, inner,
                         out);
}

}  // namespace sdb::mipgh
