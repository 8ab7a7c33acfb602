#include "schemes/mipgh/vulkan.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <vector>

#include "harness/gpu/gpu.h"
#include "schemes/mipgh/mask_table.h"
#include "schemes/mipgh/mutation.h"
#include "schemes/mipgh/primitives.h"
#include "sdb_scheme_mipgh_shaders.h"

namespace sdb::mipgh {
namespace {

namespace shaders = sdb_scheme_mipgh_shaders;
using gpu::BufferUsage;

// Invocations per work group, one target node each (local_size_x_id = 0): a multiple of every
// subgroup size in use (8 on lavapipe, 32 on NVIDIA).
constexpr uint32_t kLocalSize = 64;
constexpr uint32_t kNoPick = 0xffffffffu;

struct Push {
  uint32_t count = 0, per_item = 1, table = 0, lod_base = 0, n = 0, facet_nodes = 0, dst_base = 0, interior = 0,
           rows = 0, begins = 0, sources = 0, weight_base = 0, pick = kNoPick, facet_list = 0,
           facet_lod = 0, scatter = 0;
  float origin[4] = {0, 0, 0, 0};
};

// facets.comp's classes: a step's blocks and the limit's (facet_blocks).
constexpr uint32_t kFacetClasses = 2, kFacetStep = 0, kFacetLimit = 1;
// edges.comp's parts: a step's (edge point t and vertex point t + 1 per invocation) and the
// limit's (nodes t, t + 1).
constexpr uint32_t kEdgeParts = 2, kEdgeStep = 0, kEdgeLimit = 1;
// edges.comp's kPairs: pairs of targets per invocation.
constexpr uint32_t kEdgePairs = 2;
// base_normals.comp's parts (D-vertices, D-facet interiors, D-facet sides), and the descriptor set
// that binds level 0 as given.
constexpr uint32_t kBaseParts = 3, kBaseSet = 2;

// One dispatch: the pipeline, its push constants, and its descriptor set (reads level buffer 0 or
// 1 and writes the other, or, where the pipeline writes the output, the output).
// A level's node: (x, y, z, 0), one rgba32f texel (shaders/mipgh.glsl).
using Node = std::array<float, 4>;
struct Dispatch {
  const gpu::ComputePipeline* pipeline;
  Push push;
  uint32_t reads;
};
// Dispatches under one timestamp pair.
struct Pass {
  std::string label;
  std::vector<Dispatch> dispatches;
};

// Everything the passes read besides the levels, in three texel tables, and where each part is.
class Tables {
 public:
  std::vector<uint32_t> words{0}, lod;
  std::vector<float> weights{0};

  uint32_t add(const std::vector<uint32_t>& w) { return append(words, w); }
  uint32_t add_weights(const std::vector<float>& w) { return append(weights, w); }
  template <class T>
  static uint32_t append(std::vector<T>& to, const std::vector<T>& w) {
    const size_t at = to.size();
    to.insert(to.end(), w.begin(), w.end());
    return static_cast<uint32_t>(at);
  }
};

// facets.comp's blocks: a step's, kStepNodes nodes of level sigma side by side, (a, b) ..
// (a, b + kStepNodes - 1), and the four targets each owns at sigma + 1; the limit's, 2 x
// kLimitColumns interior nodes from (a, b). Per block one word, (a << 16 | b): the shader works out
// its targets' offsets in the interior (interior_offset, the same in facets.comp; none where a
// target is outside it), which 8 words a block read from the table had cost 8 gathers an
// invocation. Every interior target is in exactly one block. Wider blocks share more of their
// window: a step's 2 nodes read 3 x 4 nodes for 8 targets (9 for 4 apart), the limit's 2 x 4 read
// 4 x 6 (16 for 2 x 2).
constexpr uint32_t kNoTarget = 0xffffffffu;
constexpr int kStepNodes = 2, kLimitColumns = 4;  // facets.comp's constants of the same names

// Offset of node (r, c), 1-based, in an interior `width` nodes wide (triangles: row r is
// width - r long), or kNoTarget outside it.
uint32_t interior_offset(int width, bool quad, int r, int c) {
  const int row_width = quad ? width : width - r;
  if (r < 1 || r > width || c < 1 || c > row_width) return kNoTarget;
  const size_t before = quad ? size_t(r - 1) * width : size_t(r - 1) * width - size_t(r - 1) * r / 2;
  return uint32_t(before + size_t(c - 1));
}

// `limit` = false: a step's, per node (a, b + m) at level sigma, its targets (2a, 2b'),
// (2a, 2b' + 1), (2a + 1, 2b'), (2a + 1, 2b' + 1) of the interior at sigma + 1, b' = b + m (the
// nodes it owns: (r >> 1, c >> 1)). `limit` = true: the projection's, per node (a, b), a odd and
// b = 1 + kLimitColumns k, the interior nodes (a + i, b + j) at sigma, i in 0..1, j in
// 0..kLimitColumns - 1, row by row. The blocks with a target in the interior.
std::vector<uint32_t> facet_blocks(int n, bool quad, bool limit) {
  const int width = limit ? n - 2 : 2 * n - 3, first = limit ? 1 : 0;
  const int row_step = limit ? 2 : 1, column_step = limit ? kLimitColumns : kStepNodes;
  std::vector<uint32_t> table;
  for (int a = first; a < n; a += row_step)
    for (int b = first; b < n; b += column_step) {
      bool any = false;
      if (limit) {
        for (int i = 0; i < 2; ++i)
          for (int j = 0; j < kLimitColumns; ++j) any = any || interior_offset(width, quad, a + i, b + j) != kNoTarget;
      } else {
        for (int m = 0; m < kStepNodes; ++m)
          for (int i = 0; i < 2; ++i)
            for (int j = 0; j < 2; ++j)
              any = any || interior_offset(width, quad, 2 * a + i, 2 * (b + m) + j) != kNoTarget;
      }
      if (any) table.push_back(uint32_t(a) << 16 | uint32_t(b));
    }
  return table;
}

uint32_t checked_u32(size_t x, const char* what) {
  if (x >= UINT32_MAX) throw gpu::Unsupported(std::string(what) + " past 2^32 entries");
  return static_cast<uint32_t>(x);
}

class VulkanMipghEvaluation final : public Evaluation {
 public:
  VulkanMipghEvaluation(const ControlMesh& mesh, MeshRule rule, DAtlas atlas, int depth, bool project,
                        AdaptiveCriterion criterion, std::shared_ptr<gpu::Context> ctx)
      : ctx_(std::move(ctx)), control_(mesh.positions), m_(mesh, rule, std::move(atlas), depth, project, criterion) {
    const DAtlas& a = m_.atlas;
    for (int f = 0; f < a.num_facets(); ++f) (a.facet_size[f] == 4 ? has_quads_ : has_triangles_) = true;
    const uint32_t inner_nodes = m_.lod.most_nodes(m_.inner_depth());
    uint32_t nodes = m_.lod.layout(depth).num_nodes;
    if (m_.lod.adaptive()) {  // the output is what is drawn
      adaptive_ = compile_adaptive(m_.atlas, m_.lod, m_.render, m_.home, out_);
      nodes = uint32_t(out_.coords.size());
    }
    level_bytes_ = std::max<uint64_t>(uint64_t(inner_nodes) * sizeof(Node), 16);
    output_bytes_ = std::max<uint64_t>(uint64_t(nodes) * 12, 16);
    // What one texel view takes, checked before the tables are built (the D-LoD's are the largest)
    gpu::check_texel_binding(*ctx_, level_bytes_ / sizeof(Node), "a level's nodes");
    // Levels are written as storage buffers of vec4 (mipgh.glsl, kVec4) where one storage-buffer
    // binding covers them; past that, through their texel views. Either way the bits are the same.
    node_vec4_ = level_bytes_ <= ctx_->limits().max_storage_buffer_range;
    output_vec3_ = output_bytes_ <= ctx_->limits().max_storage_buffer_range;
    uint64_t lod_words_total = 0;
    for (int sigma = 0; sigma <= m_.inner_depth(); ++sigma) lod_words_total += level_lod_words(sigma);
    gpu::check_texel_binding(*ctx_, lod_words_total, "the D-LoD's index arrays");
    build_tables();
    gpu::check_memory(*ctx_,
                      {uint64_t(tables_.words.size() + tables_.weights.size() + tables_.lod.size()) * 4 +
                           3 * level_bytes_ + 2 * output_bytes_ + control_.size() * 16,
                       2 * output_bytes_ + control_.size() * 28},
                      mesh.name + " at depth " + std::to_string(depth));
    make_buffers();
    make_pipelines();
    plan_passes();
    if (!m_.lod.adaptive()) compile_primitives(m_.atlas, m_.lod, depth, out_);
    if (rule == MeshRule::QuadTri) out_.coords.clear();  // as the cpu's (cpu.cpp): no point of the reference
    out_.positions.resize(nodes);
    out_.normals.resize(nodes);
    record_frame();
    readback_.emplace(*ctx_, positions_, out_normals_, output_bytes_);
  }

  void execute() override {
    // Level 0: the control points relative to the box's centre (as the CPU's run() starts).
    const float* o = m_.origin;
    for (size_t v = 0; v < control_.size(); ++v)
      level0_[v] = {control_[v][0] - o[0], control_[v][1] - o[1], control_[v][2] - o[2], 0.0f};
    control_staging_.write(level0_);
    if (m_.project()) {  // and as given, for the normals from level 0
      for (size_t v = 0; v < control_.size(); ++v) level0_[v] = {control_[v][0], control_[v][1], control_[v][2], 0.0f};
      base_staging_.write(level0_);
    }
    ctx_->submit(*frame_);
    readback_->invalidate();
  }

  const Tessellation& result() override {
    readback_->read_into(out_);
    return out_;
  }

  size_t bytes_out() const override { return out_.positions.size() * 2 * sizeof(Point3); }

  std::optional<GpuTimes> gpu_times() const override {
    auto passes = frame_timer_->read_passes();
    if (!passes) return std::nullopt;
    readback_->append_passes(*passes);
    return gpu::to_gpu_times(*passes);
  }

 private:
  struct MaskRange {
    uint32_t entries = 0, target = 0, begins = 0, sources = 0, weights = 0;
  };
  struct LevelPasses {
    std::pair<uint32_t, uint32_t> facet_table[2];  // per kind: (facet_blocks' table, blocks per D-facet)
    uint32_t facet_lod = 0;                               // listed(): each held D-facet's D-LoD offset
    uint32_t facet_list[2] = {0, 0}, facets[2] = {0, 0};  // per kind: (D-LoD offset, first target) per D-facet listed; how many
    uint32_t fast_edges[2] = {0, 0}, num_fast_edges[2] = {0, 0};
    MaskRange masks;
  };
  struct BaseNormals {  // base_normal_tables
    MaskRange vertices;
    struct {
      uint32_t entries = 0, table = 0;
    } interiors, sides;
  };
  struct OutputNodes {  // adaptive: a level's drawn nodes, and where each goes in the output
    uint32_t at = 0, to = 0, count = 0;
  };

  bool mixed() const { return has_quads_ && has_triangles_; }
  // The limit's passes write the output themselves (kToOutput pipelines): the limit is the whole
  // output, no grid point picked from a deeper level, nothing adaptive.
  bool limit_to_output() const { return m_.project() && m_.pick.empty() && !m_.lod.adaptive(); }
  uint32_t lod_words(int sigma, bool quad) const {
    const size_t n = m_.lod.layout(sigma).n;
    return checked_u32(quad ? n * n : n * (n + 1) / 2, "a D-facet's index array");
  }
  uint64_t level_lod_words(int sigma) const {
    uint64_t words = 0;
    for (int f = 0; f < m_.atlas.num_facets(); ++f)
      if (m_.lod.holds_facet(sigma, f)) words += lod_words(sigma, m_.atlas.facet_size[f] == 4);
    return words;
  }
  // Whether the D-facet passes go through lists of D-facets (both kinds, or an adaptive level's
  // held ones) instead of addressing D-facet f at f times the array's size.
  bool listed() const { return mixed() || m_.lod.adaptive(); }
  // Nodes inside one D-facet of a kind at the level with s nodes inside a D-edge.
  static size_t interior_nodes(size_t s, bool quad) { return quad ? s * s : s * (s - 1) / 2; }

  void build_tables() {
    const int inner = m_.inner_depth();
    for (int sigma = 0; sigma <= inner; ++sigma) {
      lod_base_.push_back(checked_u32(tables_.lod.size(), "the D-LoD"));
      const uint32_t* first = m_.lod.facet(sigma, 0);
      tables_.lod.insert(tables_.lod.end(), first, first + level_lod_words(sigma));
      const auto& rows = m_.processor.side_row_table(sigma);
      rows_.push_back(tables_.add(std::vector<uint32_t>(rows.begin(), rows.end())));
      steps_.push_back(sigma < inner ? level_passes(sigma, false) : LevelPasses{});
      const bool projected = m_.project() && (m_.lod.adaptive() ? !adaptive_.nodes[sigma].empty() : sigma == inner);
      limits_.push_back(projected ? level_passes(sigma, true) : LevelPasses{});
      base_normals_.push_back(projected ? base_normal_tables(sigma) : BaseNormals{});
    }
    if (!m_.pick.empty()) pick_ = tables_.add(m_.pick);
    if (m_.lod.adaptive())
      for (const auto& level : adaptive_.nodes) {
        std::vector<uint32_t> at, to;
        for (const auto& [node, output] : level) at.push_back(node), to.push_back(output);
        outputs_.push_back({tables_.add(at), tables_.add(to), uint32_t(level.size())});
      }
  }

  // Level sigma's step to sigma + 1 (limit = false) or its projection: the D-facets the D-facet
  // passes visit, the fast D-edges, the masks of the rest. Adaptive: the step's the next level
  // holds, the projection's those whose home is this level (primitives.h).
  LevelPasses level_passes(int sigma, bool limit) {
    LevelPasses l;
    static const LevelHomes none;
    const LevelHomes& homes = m_.lod.adaptive() && limit ? adaptive_.homes[sigma] : none;
    std::vector<int32_t> facets, edges;
    if (!m_.lod.adaptive()) {
      for (int f = 0; f < m_.atlas.num_facets(); ++f) facets.push_back(f);
      for (int e = 0; e < m_.atlas.num_edges(); ++e) edges.push_back(e);
    } else {
      facets = limit ? homes.facets : m_.lod.facets_held(sigma + 1);
      edges = limit ? homes.edges : m_.lod.edges_held(sigma + 1);
    }
    for (bool quad : {false, true})
      if (quad ? has_quads_ : has_triangles_) {
        const int n = m_.lod.layout(sigma).n;
        const std::vector<uint32_t> t = facet_blocks(n, quad, limit);
        l.facet_table[quad] = {tables_.add(t), uint32_t(t.size())};
      }
    add_facet_lists(sigma, limit, facets, l);
    add_fast_edges(sigma, limit, edges, l);
    l.masks = add_masks(build_mask_table(m_.processor, *m_.shader, m_.lod, sigma, limit, homes));
    return l;
  }

  // listed(): each held D-facet's D-LoD offset at sigma (the D-edge passes), and per kind the
  // visited D-facets' (D-LoD offset, first target node); otherwise how many of each kind.
  void add_facet_lists(int sigma, bool limit, const std::vector<int32_t>& facets, LevelPasses& l) {
    if (!listed()) {
      for (bool quad : {false, true}) l.facets[quad] = (quad ? has_quads_ : has_triangles_) ? uint32_t(m_.atlas.num_facets()) : 0;
      return;
    }
    const LevelLayout& dst = m_.lod.layout(limit ? sigma : sigma + 1);
    const uint32_t* first = m_.lod.facet(sigma, 0);
    auto lod_at = [&](int f) { return uint32_t(m_.lod.facet(sigma, f) - first); };
    std::vector<uint32_t> offsets(m_.atlas.num_facets(), 0), list[2];
    for (int f = 0; f < m_.atlas.num_facets(); ++f)
      if (m_.lod.holds_facet(sigma, f)) offsets[f] = lod_at(f);
    for (int f : facets) {
      auto& to = list[m_.atlas.facet_size[f] == 4];
      to.insert(to.end(), {lod_at(f), dst.interior(f)});
    }
    l.facet_lod = tables_.add(offsets);
    for (bool quad : {false, true}) l.facet_list[quad] = tables_.add(list[quad]), l.facets[quad] = uint32_t(list[quad].size() / 2);
  }

  // The fast D-edges among `edges` (an adaptive step's: those it can read), between triangles and
  // between quads: each one's first target node, then the strip's D-facets and their side kinds.
  void add_fast_edges(int sigma, bool limit, const std::vector<int32_t>& edges, LevelPasses& l) {
    const LevelLayout& dst = m_.lod.layout(limit ? sigma : sigma + 1);
    std::vector<uint32_t> fast[2];
    for (int e : edges) {
      if (!m_.processor.fast_edge(e) || (m_.lod.adaptive() && !limit && !m_.processor.edge_readable(sigma, e))) continue;
      const DEdge& d = m_.atlas.edges[e];
      const bool quad = m_.atlas.facet_size[d.major.facet] == 4;  // fast: the minor's kind too
      const uint32_t kind = quad ? 3 : 0;  // side_row_table's kinds: a triangle's sides, then a quad's
      fast[quad].insert(fast[quad].end(), {dst.edge_node(e, 0), uint32_t(d.major.facet), kind + d.major.side,
                                           uint32_t(d.minor.facet), kind + d.minor.side});
    }
    for (bool quad : {false, true}) l.fast_edges[quad] = tables_.add(fast[quad]), l.num_fast_edges[quad] = uint32_t(fast[quad].size() / 5);
  }

  // What base_normals.comp writes after level sigma's projection: the D-vertices with tangents on
  // level 0 (vertex_tangents.h), the interiors and sides of the D-facets with patches or masks
  // (regular_patches.h, facet_masks.h), those the projection visits (adaptive: its homes).
  BaseNormals base_normal_tables(int sigma) {
    BaseNormals b;
    const LevelLayout& l = m_.lod.layout(sigma);
    std::vector<int32_t> vertices, facets, edges;
    if (m_.lod.adaptive()) {
      const LevelHomes& h = adaptive_.homes[sigma];
      vertices = h.vertices, facets = h.facets, edges = h.edges;
    } else {
      for (int v = 0; v < m_.atlas.num_vertices; ++v) vertices.push_back(v);
      for (int f = 0; f < m_.atlas.num_facets(); ++f) facets.push_back(f);
      for (int e = 0; e < m_.atlas.num_edges(); ++e) edges.push_back(e);
    }
    const BaseTangents& t = m_.base_tangents;
    std::vector<uint32_t> targets, begins{0}, sources;
    std::vector<float> weights;
    for (int v : vertices) {
      if (!t.applies(v, sigma)) continue;
      targets.push_back(uint32_t(v));
      for (uint32_t k = t.begin[size_t(v)]; k < t.begin[size_t(v) + 1]; ++k)
        sources.push_back(t.node[k]), weights.insert(weights.end(), {t.t1[k], t.t2[k]});
      begins.push_back(uint32_t(sources.size()));
    }
    b.vertices = {uint32_t(targets.size()), tables_.add(targets), tables_.add(begins), tables_.add(sources),
                  tables_.add_weights(weights)};
    if (l.s == 0) return b;
    // (node weights, control points, their count) of D-facet f, if it has them
    auto source = [&](int f, uint32_t (&entry)[3]) {
      if (m_.patches.regular(f)) {
        if (!patch_weights_.count(sigma)) patch_weights_[sigma] = tables_.add_weights(RegularPatches::node_weights(sigma));
        if (!patch_nets_) patch_nets_ = tables_.add(m_.patches.net);
        entry[0] = patch_weights_[sigma], entry[1] = patch_nets_ + 16 * uint32_t(m_.patches.patch[size_t(f)]), entry[2] = 16;
        return true;
      }
      if (!m_.facet_masks.has(f)) return false;
      const FacetMasks::Facet& g = m_.facet_masks.facets[size_t(m_.facet_masks.facet[size_t(f)])];
      const auto key = std::make_pair(g.type, sigma);
      if (!mask_weights_.count(key)) mask_weights_[key] = tables_.add_weights(m_.facet_masks.types[g.type].weights[size_t(sigma)]);
      if (!mask_control_) mask_control_ = tables_.add(m_.facet_masks.control);
      entry[0] = mask_weights_[key], entry[1] = mask_control_ + g.first, entry[2] = uint32_t(m_.facet_masks.types[g.type].size);
      return true;
    };
    std::vector<uint32_t> interiors, sides;
    uint32_t entry[3];
    for (int f : facets)
      if (m_.atlas.facet_size[f] == 4 && source(f, entry)) interiors.insert(interiors.end(), {entry[0], entry[1], entry[2], 0u, l.interior(f)});
    for (int e : edges) {
      const DEdge& d = m_.atlas.edges[e];
      if (source(d.major.facet, entry)) sides.insert(sides.end(), {entry[0], entry[1], entry[2], uint32_t(d.major.side), l.edge_node(e, 0)});
      else if (!d.minor.null() && source(d.minor.facet, entry))
        sides.insert(sides.end(), {entry[0], entry[1], entry[2], uint32_t(d.minor.side) | 4u, l.edge_node(e, 0)});
    }
    b.interiors = {uint32_t(interiors.size() / 5), tables_.add(interiors)};
    b.sides = {uint32_t(sides.size() / 5), tables_.add(sides)};
    return b;
  }

  MaskRange add_masks(const MaskTable& t) {
    return {uint32_t(t.entries()), tables_.add(t.target), tables_.add(t.begin), tables_.add(t.source),
            tables_.add_weights(t.weight)};
  }

  void make_buffers() {
    gpu::Context& c = *ctx_;
    level0_.resize(control_.size());
    const uint64_t control_bytes = std::max<uint64_t>(control_.size() * sizeof(Node), 16);
    control_staging_ = gpu::Buffer::upload(c, control_bytes, "control points (staging)");
    const BufferUsage level_usage = BufferUsage::UniformTexel | BufferUsage::StorageTexel | BufferUsage::Storage;
    level_[0] = gpu::Buffer::device(c, level_bytes_, level_usage, "level nodes (even levels)");
    level_[1] = gpu::Buffer::device(c, level_bytes_, level_usage, "level nodes (odd levels)");
    normals_ = gpu::Buffer::device(c, level_bytes_, level_usage, "limit normals");
    // Level 0 as given, for the normals taken from it (base_normals.comp)
    base_staging_ = gpu::Buffer::upload(c, control_bytes, "control points as given (staging)");
    base_ = gpu::Buffer::device(c, control_bytes, level_usage, "control points as given");
    lod_ = gpu::texel_table(c, tables_.lod, "D-LoD index arrays");
    words_ = gpu::texel_table(c, tables_.words, "mipgh tables");
    weights_ = gpu::texel_table(c, tables_.weights, "mask weights");
    const BufferUsage output_usage = BufferUsage::StorageTexel | BufferUsage::Storage | BufferUsage::Vertex;
    positions_ = gpu::Buffer::device(c, output_bytes_, output_usage, "positions");
    out_normals_ = gpu::Buffer::device(c, output_bytes_, output_usage, "normals");
  }

  // `to_output`: the pipeline writes the limit into the output (mipgh.glsl, kToOutput).
  gpu::ComputePipelineDesc desc(const char* shader, uint32_t constant1, uint32_t constant2, bool to_output = false) const {
    using gpu::Binding;
    return {shaders::get(shader),
            {Binding::UniformTexelBuffer, Binding::StorageTexelBuffer, Binding::StorageTexelBuffer,
             Binding::UniformTexelBuffer, Binding::UniformTexelBuffer, Binding::UniformTexelBuffer,
             Binding::StorageTexelBuffer, Binding::StorageTexelBuffer, Binding::UniformTexelBuffer,
             Binding::StorageBuffer, Binding::StorageBuffer, Binding::StorageBuffer, Binding::StorageBuffer},
            sizeof(Push),
            {{0, kLocalSize}, {1, constant1}, {2, constant2}, {3, to_output}, {4, node_vec4_}, {5, output_vec3_}}};
  }

  void make_pipelines() {
    for (bool quad : {false, true}) {
      if (!(quad ? has_quads_ : has_triangles_)) continue;
      for (uint32_t k = 0; k < kFacetClasses; ++k)
        facets_[quad][k] = gpu::shared_compute_pipeline(*ctx_, desc("facets.comp", quad, k));
      for (uint32_t k = 0; k < kEdgeParts; ++k) edges_[quad][k] = gpu::shared_compute_pipeline(*ctx_, desc("edges.comp", quad, k));
      if (!limit_to_output()) continue;
      facets_out_[quad] = gpu::shared_compute_pipeline(*ctx_, desc("facets.comp", quad, kFacetLimit, true));
      edges_out_[quad] = gpu::shared_compute_pipeline(*ctx_, desc("edges.comp", quad, kEdgeLimit, true));
    }
    const char* masks = ctx_->info().features.shader_float64 ? "masks_double.comp" : "masks.comp";
    masks_step_ = gpu::shared_compute_pipeline(*ctx_, desc(masks, 0, 0));
    masks_limit_ = gpu::shared_compute_pipeline(*ctx_, desc(masks, 1, 0));
    if (limit_to_output()) masks_out_ = gpu::shared_compute_pipeline(*ctx_, desc(masks, 1, 0, true));
    output_ = gpu::shared_compute_pipeline(*ctx_, desc("output.comp", m_.project(), 0));
    for (uint32_t part = 0; part < kBaseParts && m_.project(); ++part)
      base_normals_pipelines_[part] = gpu::shared_compute_pipeline(*ctx_, desc("base_normals.comp", part, 0, limit_to_output()));
    // Set k reads level buffer k and writes the other (or, a kToOutput pipeline, the output).
    constexpr VkFormat node = VK_FORMAT_R32G32B32A32_SFLOAT;
    // Bindings 9 to 12 (mipgh.glsl): the whole buffer where the pipelines store through them, a
    // token 16 bytes where they do not (past the storage-buffer range).
    const uint64_t level_range = node_vec4_ ? level_bytes_ : 16, output_range = output_vec3_ ? output_bytes_ : 16;
    // Set 2 reads level 0 as given (base_normals.comp) and writes the normals as set 0.
    for (int k = 0; k < 3; ++k)
      sets_[k] = gpu::DescriptorSet(
          *output_, {k == 2 ? base_.texels(node) : level_[k].texels(node), level_[k == 1 ? 0 : 1].texels(node), normals_.texels(node),
                     lod_.texels(VK_FORMAT_R32_UINT), words_.texels(VK_FORMAT_R32_UINT),
                     weights_.texels(VK_FORMAT_R32_SFLOAT), positions_.texels(VK_FORMAT_R32_SFLOAT),
                     out_normals_.texels(VK_FORMAT_R32_SFLOAT), normals_.texels(node),
                     level_[k == 1 ? 0 : 1].range(0, level_range), normals_.range(0, level_range), positions_.range(0, output_range),
                     out_normals_.range(0, output_range)});
  }

  // Level sigma's passes: a step to sigma + 1, or (limit) the projection at sigma, written
  // straight into the output (moved back from the box's centre) where it is the whole output.
  void add_level(int sigma, bool limit) {
    const LevelLayout& src = m_.lod.layout(sigma);
    const LevelPasses& l = limit ? limits_[sigma] : steps_[sigma];
    const bool to_output = limit && limit_to_output();
    const uint32_t reads = sigma % 2;
    Push base;
    if (to_output)
      for (int k = 0; k < 3; ++k) base.origin[k] = m_.origin[k];
    base.lod_base = lod_base_[sigma], base.n = src.n, base.rows = rows_[sigma], base.facet_lod = l.facet_lod;
    const std::string name = !limit ? "step " + std::to_string(sigma + 1)
                             : m_.lod.adaptive() ? "limit " + std::to_string(sigma) : "limit";
    // The D-facet, D-edge and mask visits write disjoint nodes from the same source level: one
    // timed pass, no barrier between their dispatches (a barrier and two timestamps cost a flush
    // each on lavapipe, 0.04 ms or more; a GPU may overlap the visits).
    Pass pass{name, {}};
    for (bool quad : {false, true}) {
      const LevelLayout& dst = m_.lod.layout(limit ? sigma : sigma + 1);
      base.facet_nodes = lod_words(sigma, quad);
      if (l.facet_table[quad].second > 0) {
        Push p = base;
        p.table = l.facet_table[quad].first, p.per_item = l.facet_table[quad].second;
        p.count = checked_u32(size_t(l.facets[quad]) * p.per_item, "a D-facet pass");
        p.dst_base = dst.facet_base;
        p.interior = checked_u32(interior_nodes(dst.s, quad), "an interior");
        p.facet_list = l.facet_list[quad];
        pass.dispatches.push_back({to_output ? &*facets_out_[quad] : &*facets_[quad][limit ? kFacetLimit : kFacetStep], p, reads});
      }
      if (l.num_fast_edges[quad] > 0) {
        Push p = base;
        p.table = l.fast_edges[quad];
        // kEdgePairs pairs along the edge: edge points 0 .. n - 2 (each with the vertex point
        // after it), or the limit's inner nodes 1 .. n - 2, 2 kEdgePairs at a time.
        p.per_item = limit ? (src.n - 2 + 2 * kEdgePairs - 1) / (2 * kEdgePairs) : (src.n - 1 + kEdgePairs - 1) / kEdgePairs;
        p.count = checked_u32(size_t(l.num_fast_edges[quad]) * p.per_item, "a D-edge pass");
        pass.dispatches.push_back({to_output ? &*edges_out_[quad] : &*edges_[quad][limit ? kEdgeLimit : kEdgeStep], p, reads});
      }
    }
    const MaskRange& r = l.masks;
    Push p = base;
    p.count = r.entries, p.table = r.target, p.begins = r.begins, p.sources = r.sources, p.weight_base = r.weights;
    pass.dispatches.push_back({to_output ? &*masks_out_ : limit ? &*masks_limit_ : &*masks_step_, p, reads});
    passes_.push_back(std::move(pass));
    if (limit) add_base_normals(sigma);
  }

  // After level sigma's projection, the normals from level 0 over its own (base_normal_tables).
  void add_base_normals(int sigma) {
    const BaseNormals& b = base_normals_[sigma];
    const int n = m_.lod.layout(sigma).n;
    Pass pass{m_.lod.adaptive() ? "limit normals " + std::to_string(sigma) : "limit normals", {}};
    Push v;
    v.count = b.vertices.entries, v.table = b.vertices.target, v.begins = b.vertices.begins;
    v.sources = b.vertices.sources, v.weight_base = b.vertices.weights;
    pass.dispatches.push_back({&*base_normals_pipelines_[0], v, kBaseSet});
    Push f;
    f.n = uint32_t(n), f.per_item = uint32_t((n - 2) * (n - 2)), f.table = b.interiors.table;
    f.count = checked_u32(size_t(b.interiors.entries) * f.per_item, "the D-facets' normals");
    pass.dispatches.push_back({&*base_normals_pipelines_[1], f, kBaseSet});
    Push s;
    s.n = uint32_t(n), s.per_item = uint32_t(n - 2), s.table = b.sides.table;
    s.count = checked_u32(size_t(b.sides.entries) * s.per_item, "the D-edges' normals");
    pass.dispatches.push_back({&*base_normals_pipelines_[2], s, kBaseSet});
    bool any = false;
    for (const Dispatch& d : pass.dispatches) any = any || d.push.count > 0;
    if (any) passes_.push_back(std::move(pass));
  }

  // Adaptive: level sigma's drawn nodes into the output, from its projection (written over the
  // other level buffer) or from the level itself.
  void add_adaptive_output(int sigma) {
    const OutputNodes& o = outputs_[sigma];
    Push p;
    p.count = o.count, p.pick = o.at, p.scatter = o.to;
    for (int k = 0; k < 3; ++k) p.origin[k] = m_.origin[k];
    passes_.push_back({"output " + std::to_string(sigma), {{&*output_, p, uint32_t((sigma + (m_.project() ? 1 : 0)) % 2)}}});
  }

  void plan_passes() {
    const int inner = m_.inner_depth();
    if (m_.lod.adaptive()) {
      for (int sigma = 0; sigma <= inner; ++sigma) {
        if (sigma > 0) add_level(sigma - 1, false);
        if (outputs_[sigma].count == 0) continue;
        if (m_.project()) add_level(sigma, true);
        add_adaptive_output(sigma);
      }
      return;
    }
    for (int sigma = 0; sigma < inner; ++sigma) add_level(sigma, false);
    if (m_.project()) add_level(inner, true);
    if (limit_to_output()) return;  // the limit wrote the output
    // The output reads the limit (written over the other buffer) or the last level.
    Push p;
    p.count = m_.lod.layout(m_.depth()).num_nodes;
    p.pick = m_.pick.empty() ? kNoPick : pick_;
    for (int k = 0; k < 3; ++k) p.origin[k] = m_.origin[k];
    passes_.push_back({"output", {{&*output_, p, uint32_t((inner + (m_.project() ? 1 : 0)) % 2)}}});
  }

  void record_frame() {
    frame_timer_.emplace(*ctx_, uint32_t(passes_.size()) + 1);
    frame_ = ctx_->record([&](gpu::Commands& cmd) {
      cmd.barrier(gpu::Stage::All, gpu::Stage::All);  // the previous frame and readback read what this one writes
      frame_timer_->reset(cmd);
      frame_timer_->begin(cmd, gpu::PassKind::Upload, "upload");
      cmd.upload(control_staging_, level_[0], control_.size() * sizeof(Node));
      if (m_.project()) cmd.upload(base_staging_, base_, control_.size() * sizeof(Node));
      frame_timer_->end(cmd);
      for (const Pass& pass : passes_) {
        // Each pass reads what the one before wrote.
        cmd.barrier(gpu::Stage::Compute, gpu::Stage::Compute);
        frame_timer_->begin(cmd, gpu::PassKind::Kernel, pass.label);
        for (const Dispatch& d : pass.dispatches) {
          if (d.push.count == 0) continue;
          cmd.bind(*d.pipeline, sets_[d.reads]);
          cmd.push(d.push);
          cmd.dispatch(gpu::groups_for(d.push.count, kLocalSize, ctx_->limits()));
        }
        frame_timer_->end(cmd);
      }
    });
  }


  std::shared_ptr<gpu::Context> ctx_;  // outlives every Vulkan object below
  std::vector<Point3> control_;
  MeshMutation m_;
  bool has_quads_ = false, has_triangles_ = false;
  bool node_vec4_ = true;    // the levels written as storage buffers of vec4 (a binding covers them)
  bool output_vec3_ = true;  // the output written as packed vec3s (mipgh.glsl, kOutVec3)
  uint64_t level_bytes_ = 0, output_bytes_ = 0;
  Tables tables_;
  std::vector<uint32_t> lod_base_, rows_;
  std::vector<LevelPasses> steps_, limits_;  // per level: its step to the next, its projection
  AdaptiveOutput adaptive_;
  std::vector<OutputNodes> outputs_;  // adaptive, per level
  uint32_t pick_ = 0;
  std::vector<Pass> passes_;
  std::vector<Node> level0_;
  gpu::Buffer control_staging_, level_[2], normals_, lod_, words_, weights_;
  gpu::Buffer base_staging_, base_;  // level 0 as given (base_normals.comp)
  std::vector<BaseNormals> base_normals_;  // per level: what base_normals.comp writes after its projection
  std::map<int, uint32_t> patch_weights_;  // per level: RegularPatches::node_weights in the weights
  std::map<std::pair<uint32_t, int>, uint32_t> mask_weights_;  // per mask type and level
  uint32_t patch_nets_ = 0, mask_control_ = 0;
  gpu::Buffer positions_, out_normals_;
  std::optional<gpu::OutputReadback> readback_;
  // The context's (gpu::shared_compute_pipeline: lavapipe compiles each once).
  std::shared_ptr<const gpu::ComputePipeline> facets_[2][kFacetClasses], edges_[2][kEdgeParts], masks_step_, masks_limit_, output_;
  std::shared_ptr<const gpu::ComputePipeline> facets_out_[2], edges_out_[2], masks_out_;  // the limit into the output
  gpu::DescriptorSet sets_[3];
  std::shared_ptr<const gpu::ComputePipeline> base_normals_pipelines_[3];
  std::optional<gpu::GpuTimer> frame_timer_;
  std::optional<gpu::Recording> frame_;
  Tessellation out_;
};

}  // namespace

std::optional<std::string> vulkan_unavailable() {
  static const gpu::DeviceInfo device = gpu::probe();
  if (!device.available) return "no Vulkan device: " + device.reason;
  if (!device.features.scalar_block_layout)
    return device.name + " lacks scalarBlockLayout; the MiPGH limit stores packed vec3s";
  return std::nullopt;  // nine texel and four storage bindings per pass: within Vulkan's minimum limits
}

std::unique_ptr<Evaluation> make_vulkan_evaluation(const ControlMesh& mesh, MeshRule rule, DAtlas atlas,
                                                   int depth, bool project_to_limit, AdaptiveCriterion criterion) {
  if (auto why = vulkan_unavailable()) throw gpu::Unsupported(*why);
  return std::make_unique<VulkanMipghEvaluation>(mesh, rule, std::move(atlas), depth, project_to_limit, criterion,
                                                 gpu::shared_context());
}

}  // namespace sdb::mipgh
