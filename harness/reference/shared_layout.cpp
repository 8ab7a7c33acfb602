#include "harness/reference/shared_layout.h"

#include <opensubdiv/bfr/parameterization.h>
#include <opensubdiv/bfr/tessellation.h>
#include <opensubdiv/far/ptexIndices.h>

#include <stdexcept>

namespace sdb {

namespace Bfr = OpenSubdiv::Bfr;
namespace Far = OpenSubdiv::Far;

namespace {

constexpr uint32_t kUnset = ~0u;

class LayoutBuilder {
 public:
  LayoutBuilder(const Far::TopologyRefiner& r, SubdivisionRule rule, int segments)
      : level_(r.GetLevel(0)), ptex_(r), rule_(rule), segments_(segments) {
    vertex_index_.assign(level_.GetNumVertices(), kUnset);
    edge_first_.assign(level_.GetNumEdges(), kUnset);
    out_.owned_by_face.resize(level_.GetNumFaces());
  }

  SharedLayout build() {
    for (int f = 0; f < level_.GetNumFaces(); ++f)
      if (!level_.IsFaceHole(f)) add_face(f);
    return std::move(out_);
  }

 private:
  uint32_t new_vertex(int face, const Bfr::Parameterization& param, const float uv[2]) {
    const uint32_t id = static_cast<uint32_t>(out_.topology.coords.size());
    out_.topology.coords.push_back(ptex_coord(face, param, uv));
    out_.owned_by_face[face].push_back({id, uv[0], uv[1]});
    return id;
  }

  SurfaceCoord ptex_coord(int face, const Bfr::Parameterization& param, const float uv[2]) const {
    const uint32_t first = static_cast<uint32_t>(ptex_.GetFaceId(face));
    if (!param.HasSubFaces()) return {first, uv[0], uv[1]};
    float sub[2];
    const int k = param.ConvertCoordToNormalizedSubFace(uv, sub);
    return {first + static_cast<uint32_t>(k), sub[0], sub[1]};
  }

  void add_face(int f) {
    Far::ConstIndexArray fv = level_.GetFaceVertices(f), fe = level_.GetFaceEdges(f);
    const int n = fv.size();
    const Bfr::Parameterization param(rule_ == SubdivisionRule::Loop ? OpenSubdiv::Sdc::SCHEME_LOOP
                                                                      : OpenSubdiv::Sdc::SCHEME_CATMARK, n);
    Bfr::Tessellation::Options opts;
    opts.SetFacetSize(3);
    const Bfr::Tessellation tess(param, segments_, opts);
    if (!tess.IsValid()) throw std::runtime_error("Bfr::Tessellation rejected face " + std::to_string(f));
    std::vector<float> uv(2 * tess.GetNumCoords());
    tess.GetCoords(uv.data());
    // Boundary coords run corner 0, edge 0's interior points, corner 1, ... counter-clockwise;
    // interior coords follow.
    std::vector<uint32_t> local(tess.GetNumCoords());
    const int per_edge = segments_ - 1;
    for (int k = 0; k < n; ++k) {
      const int corner = k * segments_;
      float expected[2];
      param.GetVertexCoord(k, expected);
      if (uv[2 * corner] != expected[0] || uv[2 * corner + 1] != expected[1])
        throw std::logic_error("Bfr::Tessellation boundary order is not corner-first as assumed");
      uint32_t& vid = vertex_index_[fv[k]];
      if (vid == kUnset) vid = new_vertex(f, param, &uv[2 * corner]);
      local[corner] = vid;
      const int e = fe[k];
      const bool forward = level_.GetEdgeVertices(e)[0] == fv[k];
      if (edge_first_[e] == kUnset) {
        edge_first_[e] = static_cast<uint32_t>(out_.topology.coords.size());
        // Allocate in the edge's own direction so the other face can index them the same way.
        for (int j = 0; j < per_edge; ++j) {
          const int local_j = forward ? j : per_edge - 1 - j;
          new_vertex(f, param, &uv[2 * (corner + 1 + local_j)]);
        }
      }
      for (int j = 0; j < per_edge; ++j) local[corner + 1 + j] = edge_first_[e] + (forward ? j : per_edge - 1 - j);
    }
    for (int i = n * segments_; i < tess.GetNumCoords(); ++i) local[i] = new_vertex(f, param, &uv[2 * i]);
    std::vector<int> facets(3 * tess.GetNumFacets());
    tess.GetFacets(facets.data());
    for (int idx : facets) out_.topology.triangles.push_back(local[idx]);
  }

  const Far::TopologyLevel& level_;
  const Far::PtexIndices ptex_;
  SubdivisionRule rule_;
  int segments_;
  std::vector<uint32_t> vertex_index_, edge_first_;
  SharedLayout out_;
};

}  // namespace

SharedLayout make_shared_layout(const Far::TopologyRefiner& refiner, SubdivisionRule rule, int segments) {
  if (segments < 1) throw std::invalid_argument("shared layout needs at least one segment per edge");
  return LayoutBuilder(refiner, rule, segments).build();
}

}  // namespace sdb
