#include "schemes/fragments/device_tables.h"

#include <algorithm>
#include <bit>
#include <limits>

#include "harness/core/errors.h"

namespace sdb::fragments {
namespace {

class Packer {
 public:
  explicit Packer(std::vector<uint32_t>& words) : w_(words) {}

  uint32_t at() const { return static_cast<uint32_t>(w_.size()); }
  void word(uint32_t v) { w_.push_back(v); }
  void number(float v) { w_.push_back(std::bit_cast<uint32_t>(v)); }
  template <class T>
  uint32_t list(const std::vector<T>& values) {
    const uint32_t begin = at();
    for (const T& v : values) {
      if constexpr (std::is_same_v<T, float>) number(v);
      else word(static_cast<uint32_t>(v));
    }
    return begin;
  }

  // Rules start at a multiple of 4 words and fill whole ones (device_tables.h): the shaders read
  // them as uvec4 texels.
  void align() {
    while (w_.size() % 4) w_.push_back(0);
  }
  template <class T>
  uint32_t aligned_list(const std::vector<T>& values) {
    align();
    return list(values);
  }
  uint32_t faces(const std::vector<FaceRule>& rules) {
    align();
    const uint32_t begin = at();
    for (const FaceRule& r : rules) word(r.a), word(r.b), word(r.c), word(r.d);
    return begin;
  }
  uint32_t edges(const std::vector<EdgeRule>& rules) {
    align();
    const uint32_t begin = at();
    for (const EdgeRule& r : rules) {
      word(r.v0), word(r.v1), word(r.f0), word(r.f1), number(r.wv), number(r.wf), word(0), word(0);
    }
    return begin;
  }
  uint32_t vertices(const std::vector<VertexRule>& rules) {
    align();
    const uint32_t begin = at();
    for (const VertexRule& r : rules) {
      word(r.centre), word(r.p0), word(r.p1), word(r.ring), word(uint32_t(r.num_e) | uint32_t(r.num_f) << 16);
      number(r.wv), number(r.wc), number(r.we), number(r.wf), word(0), word(0), word(0);
    }
    return begin;
  }

 private:
  std::vector<uint32_t>& w_;
};

// The net tangents (tables.h) as limit.comp's net_normal reads them: per block its support
// (net_support) padded to an even count with slot 0 (the origin: it adds 0), and per entry the
// weight pairs (w1, w2) of its block's support in that order, `stride` words apart (a multiple of
// 4), so that one uvec4 texel holds two control points' weights.
struct NetPairs {
  std::vector<uint32_t> support_begin, support;
  std::vector<float> pairs;
  uint32_t stride = 0;
};
NetPairs net_pairs(const ShapeTables& t) {
  const LimitTable& lim = t.limit;
  NetPairs out;
  if (!lim.net_size || lim.net_support_begin.size() < 2) return out;
  const uint32_t n = lim.net_size, blocks = uint32_t(lim.net_support_begin.size() - 1);
  const size_t per_block = t.block_vertices() / blocks;
  out.support_begin = {0};
  for (uint32_t b = 0; b < blocks; ++b) {
    out.support.insert(out.support.end(), lim.net_support.begin() + lim.net_support_begin[b],
                       lim.net_support.begin() + lim.net_support_begin[b + 1]);
    if (out.support.size() % 2) out.support.push_back(0);
    out.support_begin.push_back(uint32_t(out.support.size()));
    out.stride = std::max(out.stride, 2 * (out.support_begin[b + 1] - out.support_begin[b]));
  }
  out.stride = (out.stride + 3) / 4 * 4;
  out.pairs.assign(t.block_vertices() * out.stride, 0.0f);
  for (size_t i = 0; i < t.block_vertices(); ++i) {
    const uint32_t b = uint32_t(i / per_block);
    for (uint32_t k = out.support_begin[b]; k < out.support_begin[b + 1]; ++k) {
      const uint32_t j = out.support[k];
      if (j == 0) continue;  // padding
      out.pairs[i * out.stride + 2 * (k - out.support_begin[b])] = lim.net_tangents[i * 2 * n + j];
      out.pairs[i * out.stride + 2 * (k - out.support_begin[b]) + 1] = lim.net_tangents[i * 2 * n + n + j];
    }
  }
  return out;
}

// Rules first, then the header (the words may move while the rules go in).
void pack_shape(const ShapeTables& t, uint32_t header, std::vector<uint32_t>& words) {
  Packer p(words);
  for (size_t d = 0; d < t.levels.size(); ++d) {
    const LevelTable& l = t.levels[d];
    const uint32_t faces = p.faces(l.faces), edges = p.edges(l.edges), vertices = p.vertices(l.vertices);
    const uint32_t ring = p.list(l.ring);
    uint32_t* h = words.data() + header + kHeaderPerLevel * d;
    h[0] = l.num_slots, h[1] = uint32_t(l.faces.size()), h[2] = faces, h[3] = uint32_t(l.edges.size()), h[4] = edges;
    h[5] = uint32_t(l.vertices.size()), h[6] = vertices, h[7] = ring;
  }
  const LimitTable& lim = t.limit;
  uint32_t f[kHeaderLimit] = {};
  f[kNumPositions] = uint32_t(lim.position.size());
  f[kPositions] = p.vertices(lim.position);
  f[kLimitRing] = p.list(lim.ring);
  f[kStencil] = p.list(lim.stencil);
  f[kStencilBegin] = p.list(lim.stencil_begin);
  f[kStencilSlot] = p.list(lim.stencil_slot);
  f[kStencilW] = p.list(lim.stencil_w);
  f[kRegular] = p.list(lim.regular);
  f[kRegularSize] = uint32_t(lim.regular_size);
  f[kRegularSlots] = p.list(lim.regular_slots);
  f[kTangentBegin] = p.list(lim.tangent_begin);
  f[kTangentSlot] = p.list(lim.tangent_slot);
  f[kTangentW1] = p.list(lim.tangent_w1);
  f[kTangentW2] = p.list(lim.tangent_w2);
  f[kBlockVertices] = uint32_t(t.block_vertices());
  f[kNumSlots0] = t.num_slots0;
  f[kNetSize] = lim.net_size;
  const NetPairs net = net_pairs(t);
  f[kNetStride] = net.stride;
  f[kNetTangents] = p.aligned_list(net.pairs);
  f[kNetSupportBegin] = p.list(net.support_begin);
  f[kNetSupport] = p.list(net.support);
  f[kBlockSize] = uint32_t(t.block_vertices() / std::max(t.owned_faces, 1));
  if (!lim.patch_weights.empty()) {
    f[kPatchSegments] = uint32_t(lim.patch_segments);
    f[kPatchWeights] = p.list(lim.patch_weights);
    std::vector<float> params;  // kernel.cpp's u and v, float(i) / float(s): a GPU's division may round otherwise
    for (int i = 0; i <= lim.patch_segments; ++i) params.push_back(float(i) / float(lim.patch_segments));
    f[kPatchParams] = p.list(params);
  }
  std::copy(f, f + kHeaderLimit, words.data() + header + kHeaderPerLevel * t.levels.size());
}

}  // namespace

DeviceTables pack_tables(const FragmentSurface& s) {
  DeviceTables out;
  out.levels = static_cast<uint32_t>(s.inner_depth);
  out.header_words = kHeaderPerLevel * out.levels + kHeaderLimit;
  out.words.assign(size_t(out.header_words) * s.tables.size(), 0);
  for (size_t shape = 0; shape < s.tables.size(); ++shape)
    pack_shape(s.tables[shape], static_cast<uint32_t>(shape * out.header_words), out.words);
  if (s.num_output_vertices > std::numeric_limits<uint32_t>::max())
    throw Unsupported("the output has 2^32 vertices or more");
  for (uint32_t f : s.order) {
    const std::vector<int>& control = s.partition.fragments[f].control;
    out.fragments.push_back(static_cast<uint32_t>(out.words.size()));
    out.fragments.push_back(static_cast<uint32_t>(s.first_vertex[f]));
    out.fragments.push_back(static_cast<uint32_t>(s.partition.fragments[f].shape));
    out.words.insert(out.words.end(), control.begin(), control.end());
    if (out.words.size() > std::numeric_limits<uint32_t>::max())
      throw Unsupported("the pattern tables pass 2^32 words");
  }
  return out;
}

namespace {

RingCase ring_case(uint32_t n) {
  switch (n) {
    case 0: return kRingNone;
    case 1: return kRingOne;
    case 2: return kRingTwo;
    case 4: return kRingFour;
    case 6: return kRingSix;
    case 8: return kRingEight;
    default: return kRingSorted;
  }
}

}  // namespace

uint32_t rule_kind(const VertexRule& r) {
  return ring_case(r.num_e) | ring_case(r.num_f) << 3 | (r.wc != 0.0f ? 64u : 0u);
}

uint32_t limit_kind(const ShapeTables& t, uint32_t entry, bool project) {
  const LimitTable& lim = t.limit;
  const NormalCase normal = !lim.patch_weights.empty()  ? kNormalPatch
                            : lim.net_size               ? kNormalNet
                            : lim.regular[entry] < 0     ? kNormalGeneral
                            : lim.regular_size == 9      ? kNormalRegular9
                            : lim.regular_size == 7      ? kNormalRegular7
                                                         : kNormalAny;
  if (!project) return kind_of(0, kPositionRule, normal);
  if (lim.stencil[entry] >= 0) return kind_of(0, kPositionStencil, normal);
  return kind_of(rule_kind(lim.position[entry]), kPositionRule, normal);
}

uint32_t append_kind_lists(DeviceTables& d, const std::vector<std::vector<std::vector<uint32_t>>>& lists) {
  const size_t pairs = d.words.size();
  for (const auto& by_shape : lists) d.words.resize(d.words.size() + 2 * by_shape.size());
  size_t pair = pairs;
  for (const auto& by_shape : lists)
    for (const std::vector<uint32_t>& entries : by_shape) {
      d.words[pair++] = static_cast<uint32_t>(d.words.size());
      d.words[pair++] = static_cast<uint32_t>(entries.size());
      d.words.insert(d.words.end(), entries.begin(), entries.end());
    }
  if (d.words.size() > std::numeric_limits<uint32_t>::max()) throw Unsupported("the pattern tables pass 2^32 words");
  return static_cast<uint32_t>(pairs);
}

}  // namespace sdb::fragments
