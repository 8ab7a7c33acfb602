// Internal to the scheme: the builder of a shape's pattern tables (tables.h), refinement in
// tables.cpp, the limit entries in limit_tables.cpp.
#pragma once

#include <opensubdiv/far/topologyRefiner.h>
#include <opensubdiv/sdc/catmarkScheme.h>
#include <opensubdiv/sdc/loopScheme.h>
#include <opensubdiv/sdc/scheme.h>

#include <algorithm>
#include <array>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "harness/core/errors.h"
#include "harness/mesh/osd_topology.h"
#include "harness/reference/sdc_hoods.h"
#include "schemes/fragments/tables.h"

namespace sdb::fragments::detail {

namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;
using Mask = SdcMask;

// The kernel's ring sums take at most this many terms.
constexpr int kMaxValence = 1024;

// Shapes with more level-0 slots keep the last level's tangents (net_tangents.cpp): the weights
// cost 2 floats per slot for every tangent entry, and a net this large is a vertex of valence
// 20 or more, where the ring shrinks no faster than a regular one.
constexpr uint32_t kMaxTangentNet = 64;

// Adds LimitTable::net_tangents to a finished shape.
void add_net_tangents(ShapeTables& t, bool catmark);

// Sdc's tangent masks at a regular vertex, in the order centre, ring, opposite vertices.
struct RegularTangents {
  std::vector<double> first, second;
};
const RegularTangents& regular_tangents(bool catmark);

[[noreturn]] void asymmetric(const char* what);

// wv c + (weights on the ring) as wv c + wc (p0 + p1) + we sum(e) + wf sum(f); throws Unsupported
// where the weights have no such form (tables.cpp).
VertexRule vertex_rule(uint32_t centre, float wv, const std::vector<float>& ew, const std::vector<uint32_t>& eref,
                       const std::vector<float>& fw, const std::vector<uint32_t>& fref, std::vector<uint32_t>& ring,
                       const char* what);

// A face of the owned region at some level: which owned face it lies in and its corners' ptex
// grid coordinates in units of 2^-depth.
struct RegionFace {
  int face, owner;
  std::array<std::array<int, 2>, 4> uv;
};

template <Sdc::SchemeType S>
class TableBuilder {
 public:
  TableBuilder(const LocalNet& net, SubdivisionRule rule, int depth, int out_depth)
      : rule_(rule), depth_(depth), out_depth_(out_depth), refiner_(make_refiner(net.mesh, rule)),
        num_owned_(net.num_owned) {
    Far::TopologyRefiner::UniformOptions options(depth);
    options.fullTopologyInLastLevel = true;
    refiner_->RefineUniform(options);
    scheme_ = Sdc::Scheme<S>(refiner_->GetSchemeOptions());
  }

  ShapeTables build();

 private:
  static constexpr bool kCatmark = S == Sdc::SCHEME_CATMARK;

  std::vector<RegionFace> base_region() const;

  uint32_t parent_slot(int v) const;

  std::vector<RegionFace> child_region(const Far::TopologyLevel& parent, const Far::TopologyLevel& child) const;

  // The points of level d a fragment keeps: its region's vertices and every vertex of a face
  // touching one of them.
  std::vector<char> needed_vertices(const Far::TopologyLevel& level) const;

  LevelTable refine_level(int d);

  FaceRule face_rule(const Far::TopologyLevel& parent, int f) const;

  // For Catmull-Clark the face weights apply to the child face points (Far's face centres), for
  // Loop to the vertex opposite the edge in each face, as PrimvarRefiner applies them.
  EdgeRule edge_rule(const Far::TopologyLevel& parent, const Far::TopologyLevel& child, int e,
                     const std::vector<int>& child_slot) const;

  VertexRule vertex_rule_at(const Far::TopologyLevel& parent, const Far::TopologyLevel& child, int v,
                            const std::vector<int>& child_slot, std::vector<uint32_t>& ring) const;

  // Limit masks as PrimvarRefiner::Limit takes them: the last level's vertex rule, face weights
  // on the vertex opposite in each face. Positions are one per vertex; tangents one per vertex
  // and side: at a crease or corner the surface has a normal on each side, and each owned face
  // takes the one of its own side (Far's masks give the side the vertex's ring starts in).
  void make_limit(ShapeTables& t) const;

  // Which of a vertex's sides face f lies on: for a corner the face's slot in the ring (-1 - slot);
  // for an interior crease the ring rotation that puts f between the leading and trailing crease
  // edges; 0 for everything else.
  int side_of(const Far::TopologyLevel& last, int v, int f) const;

  std::vector<uint32_t> ring_vertices(const Far::TopologyLevel& last, int v, int start) const;

  std::vector<uint32_t> opposite_vertices(const Far::TopologyLevel& last, int v, int start) const;

  static std::vector<float> weights(int count, const float& (Mask::*at)(int) const, const Mask& m);

  // A dart's limit, or a smooth valence-2 vertex's, from the eigenvector of its ring's matrix
  // (ring_limit.h): a dart's ring starts at its sharp edge, the same in every fragment.
  bool add_exact_limit_position(const Far::TopologyLevel& last, int v, LimitTable& lim) const;

  void add_limit_position(const Far::TopologyLevel& last, int v, LimitTable& lim) const;


  // Tangents of v on `side` (side_of), `face` a face of that side.
  void add_limit_tangents(const Far::TopologyLevel& last, int v, int side, int face, LimitTable& lim) const;

  bool stationary(const Far::TopologyLevel& last, int v) const;
  bool add_exact_limit_tangents(const Far::TopologyLevel& last, int v, int face,
                                std::map<uint32_t, std::pair<float, float>>& tangent) const;

  // The regular vertex's tangents, in Sdc's order (centre, ring, opposite vertices); false where
  // the vertex is not regular or its weights differ from the first regular vertex's.
  bool add_regular_tangents(const Far::TopologyLevel& last, int v, const Mask& t1, const Mask& t2,
                            const std::vector<uint32_t>& eref, const std::vector<uint32_t>& fref, LimitTable& lim) const;

  SubdivisionRule rule_;
  int depth_, out_depth_;
  std::unique_ptr<Far::TopologyRefiner> refiner_;
  int num_owned_;
  Sdc::Scheme<S> scheme_;
  std::vector<int> slot_;  // local vertex of the current level -> slot, or -1
  std::vector<RegionFace> region_;
};

}  // namespace sdb::fragments::detail
