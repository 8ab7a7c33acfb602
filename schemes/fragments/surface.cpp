#include "schemes/fragments/surface.h"

#include "harness/core/errors.h"
#include "harness/mesh/osd_topology.h"
#include "schemes/fragments/kernel.h"

#include <algorithm>
#include <cmath>

namespace sdb::fragments {

size_t output_vertices(const ControlMesh& mesh, SubdivisionRule rule, int depth) {
  return (mesh.face_sizes.size() - mesh.holes.size()) * static_cast<size_t>(block_size(rule, depth));
}

// The same for every fragment: a point shared by two fragments must come from the same level in
// both to be bit-identical.
int inner_depth_for(const ControlMesh& mesh, int depth) { return limit_depth_for(mesh, depth); }

FragmentSurface::FragmentSurface(const ControlMesh& mesh, SubdivisionRule r, int d, int inner)
    : rule(r), depth(d), inner_depth(inner), partition(partition_mesh(mesh, r)) {
  if (inner > d) {
    // Each shape's tables hold every level of its net down to the inner depth: refused up front
    // where they would not fit (catmark_gregory_test7's sharpness 9 at depth 1: 1 GB).
    double faces = 0;
    for (const LocalNet& net : partition.shapes) faces += static_cast<double>(num_faces(net.mesh));
    if (auto why = limit_depth_refusal(mesh, d, faces, kMaxInnerFaces)) throw Unsupported(*why);
  }
  for (const LocalNet& net : partition.shapes) {
    tables.push_back(build_tables(net, rule, inner_depth, depth));
    max_slots = std::max(max_slots, tables.back().max_slots);
    const LimitTable& lim = tables.back().limit;
    max_limit_entries = std::max({max_limit_entries, static_cast<uint32_t>(lim.position.size()),
                                  static_cast<uint32_t>(lim.regular.size())});
  }
  order.resize(partition.fragments.size());
  for (uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    return partition.fragments[a].shape < partition.fragments[b].shape;
  });
  // Blocks follow `order`, so that any run of batches writes one contiguous range (the Vulkan
  // backend's waves, vulkan.h).
  const size_t bs = block_size(rule, depth);
  first_vertex.resize(partition.fragments.size());
  for (uint32_t f : order) {
    first_vertex[f] = num_output_vertices;
    num_output_vertices += partition.fragments[f].owned_faces.size() * bs;
  }
  batches = batches_of(kLanes);
}

std::vector<FragmentSurface::Batch> FragmentSurface::batches_of(uint32_t max_count) const {
  std::vector<Batch> out;
  for (uint32_t i = 0; i < order.size();) {
    uint32_t n = 1;
    while (i + n < order.size() && n < max_count &&
           partition.fragments[order[i + n]].shape == partition.fragments[order[i]].shape)
      ++n;
    out.push_back({i, n});
    i += n;
  }
  return out;
}

namespace {

// A block's grid point (u, v), the block's (0, 0) at the face's corner `start`, in the face's own
// ptex parametrization (corner 0 at (0, 0)). Each turn by one corner: a quad's (u, v) -> (1 - v, u),
// a triangle's -> (1 - u - v, u). Exact on the grid: every value is a multiple of 2^-depth.
SurfaceCoord in_face(SubdivisionRule rule, int start, uint32_t face, SurfaceCoord c) {
  for (int turn = 0; turn < start; ++turn)
    c = rule == SubdivisionRule::Loop ? SurfaceCoord{face, 1.0f - c.u - c.v, c.u} : SurfaceCoord{face, 1.0f - c.v, c.u};
  c.face = face;
  return c;
}

}  // namespace

void FragmentSurface::describe(Tessellation& out) const {
  const int bs = block_size(rule, depth);
  const std::vector<uint32_t> pattern = block_triangles(rule, depth);
  const float inv = 1.0f / static_cast<float>(1 << depth);
  out.triangles.clear();
  out.triangles.reserve(num_output_vertices / bs * pattern.size());
  out.coords.resize(num_output_vertices);
  std::vector<SurfaceCoord> grid(bs);
  for (int j = 0, s = 1 << depth; j <= s; ++j)
    for (int i = 0; i <= s; ++i)
      if (rule != SubdivisionRule::Loop || i + j <= s)
        grid[block_index(rule, depth, i, j)] = {0, static_cast<float>(i) * inv, static_cast<float>(j) * inv};
  for (size_t f = 0; f < partition.fragments.size(); ++f) {
    const Fragment& fragment = partition.fragments[f];
    for (size_t k = 0; k < fragment.owned_faces.size(); ++k) {
      const size_t base = first_vertex[f] + k * bs;
      for (uint32_t t : pattern) out.triangles.push_back(static_cast<uint32_t>(base + t));
      const auto face = static_cast<uint32_t>(fragment.owned_faces[k]);
      for (int b = 0; b < bs; ++b) out.coords[base + b] = in_face(rule, fragment.owned_starts[k], face, grid[b]);
    }
  }
}

FragmentStats FragmentSurface::stats() const {
  FragmentStats s;
  s.fragments = static_cast<int>(partition.fragments.size());
  s.vertex_patches = partition.vertex_patches;
  s.facet_patches = partition.facet_patches;
  s.shapes = static_cast<int>(tables.size());
  for (const ShapeTables& t : tables) {
    for (const LevelTable& l : t.levels)
      s.table_bytes += l.faces.size() * sizeof(FaceRule) + l.edges.size() * sizeof(EdgeRule) +
                       l.vertices.size() * sizeof(VertexRule) + l.ring.size() * sizeof(uint32_t);
    s.table_bytes += t.limit.position.size() * sizeof(VertexRule) + t.limit.ring.size() * 4 +
                     t.limit.tangent_slot.size() * 12 + t.limit.regular_slots.size() * 4;
  }
  return s;
}

}  // namespace sdb::fragments
