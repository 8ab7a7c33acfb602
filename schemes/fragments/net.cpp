#include "schemes/fragments/net.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <unordered_map>
#include <utility>

#include "harness/core/errors.h"
#include "harness/mesh/osd_topology.h"

namespace sdb::fragments {
namespace {

namespace Far = OpenSubdiv::Far;

// The regular valence of an interior vertex, and of a boundary one in faces.
bool extraordinary(const Far::TopologyLevel& level, int v, SubdivisionRule rule) {
  const int faces = level.GetVertexFaces(v).size();
  const bool loop = rule == SubdivisionRule::Loop;
  if (level.IsVertexBoundary(v)) return faces != (loop ? 3 : 2);
  return faces != (loop ? 6 : 4);
}

struct GlobalTags {
  std::map<std::pair<int, int>, float> creases;  // (lower, higher vertex) -> sharpness
  std::unordered_map<int, float> corners;
  std::vector<char> hole;
};

GlobalTags global_tags(const ControlMesh& mesh) {
  GlobalTags t;
  for (const EdgeCrease& c : mesh.creases)
    t.creases[{std::min(c.v0, c.v1), std::max(c.v0, c.v1)}] = c.sharpness;
  for (const VertexCorner& c : mesh.corners) t.corners[c.vertex] = c.sharpness;
  t.hole.assign(mesh.face_sizes.size(), 0);
  for (int f : mesh.holes) t.hole[f] = 1;
  return t;
}

class NetBuilder {
 public:
  NetBuilder(const ControlMesh& mesh, const Far::TopologyLevel& level, const std::vector<int>& offsets,
             const GlobalTags& tags)
      : mesh_(mesh), level_(level), offsets_(offsets), tags_(tags) {}

  // The net of `owned` (global faces, each taken from its corner `starts[k]` on: the corner at
  // its output block's (0, 0)), its control vertices, and the key that names its shape.
  std::pair<LocalNet, std::vector<int>> build(const std::vector<int>& owned, const std::vector<int>& starts,
                                              std::vector<int32_t>& key) {
    local_.clear();
    control_.clear();
    faces_.clear();
    for (size_t k = 0; k < owned.size(); ++k) add_face(owned[k], starts[k]);
    const int region_vertices = static_cast<int>(control_.size());
    for (int i = 0; i < region_vertices; ++i) add_ring(control_[i], owned);
    return {make_net(static_cast<int>(owned.size()), key), control_};
  }

 private:
  int label(int global) {
    auto [it, fresh] = local_.try_emplace(global, static_cast<int>(control_.size()));
    if (fresh) control_.push_back(global);
    return it->second;
  }

  // Face f, its vertices taken from position `start` on.
  void add_face(int f, int start) {
    const int n = mesh_.face_sizes[f];
    for (int k = 0; k < n; ++k) label(mesh_.face_vertices[offsets_[f] + (start + k) % n]);
    faces_.push_back({f, start});
  }

  bool has_face(int f) const {
    return std::any_of(faces_.begin(), faces_.end(), [f](const auto& e) { return e.first == f; });
  }

  // The faces around global vertex v, from its first owned face on (Far orders them around v).
  void add_ring(int v, const std::vector<int>& owned) {
    Far::ConstIndexArray vf = level_.GetVertexFaces(v);
    int first = 0, best = static_cast<int>(owned.size());
    for (int i = 0; i < vf.size(); ++i) {
      const int rank = static_cast<int>(std::find(owned.begin(), owned.end(), vf[i]) - owned.begin());
      if (rank < best) best = rank, first = i;
    }
    for (int i = 0; i < vf.size(); ++i) {
      const int f = vf[(first + i) % vf.size()];
      if (has_face(f)) continue;
      int start = 0;
      while (mesh_.face_vertices[offsets_[f] + start] != v) ++start;
      add_face(f, start);
    }
  }

  LocalNet make_net(int num_owned, std::vector<int32_t>& key) {
    LocalNet net;
    net.num_owned = num_owned;
    ControlMesh& m = net.mesh;
    m.name = mesh_.name + " fragment";
    m.source = mesh_.source;
    m.boundary = mesh_.boundary;
    m.crease_method = mesh_.crease_method;
    m.triangle_rule = mesh_.triangle_rule;
    m.positions.assign(control_.size(), Point3{0, 0, 0});
    key = {static_cast<int32_t>(faces_.size()), num_owned, static_cast<int32_t>(control_.size())};
    for (size_t i = 0; i < faces_.size(); ++i) {
      const auto [f, start] = faces_[i];
      const int n = mesh_.face_sizes[f];
      m.face_sizes.push_back(n);
      key.push_back(n);
      for (int k = 0; k < n; ++k) {
        const int local = local_.at(mesh_.face_vertices[offsets_[f] + (start + k) % n]);
        m.face_vertices.push_back(local);
        key.push_back(local);
      }
      if (tags_.hole[f]) m.holes.push_back(static_cast<int>(i));
    }
    key.push_back(static_cast<int32_t>(m.holes.size()));
    key.insert(key.end(), m.holes.begin(), m.holes.end());
    add_tags(m, key);
    return net;
  }

  // Creases on the net's edges and corners on its vertices, in a label order (for the key).
  void add_tags(ControlMesh& m, std::vector<int32_t>& key) {
    std::map<std::pair<int, int>, float> creases;
    if (!tags_.creases.empty())
      for (size_t f = 0, o = 0; f < m.face_sizes.size(); o += m.face_sizes[f], ++f)
        for (int k = 0; k < m.face_sizes[f]; ++k) {
          const int a = m.face_vertices[o + k], b = m.face_vertices[o + (k + 1) % m.face_sizes[f]];
          const int ga = control_[a], gb = control_[b];
          auto it = tags_.creases.find({std::min(ga, gb), std::max(ga, gb)});
          if (it != tags_.creases.end()) creases[{std::min(a, b), std::max(a, b)}] = it->second;
        }
    key.push_back(static_cast<int32_t>(creases.size()));
    for (const auto& [edge, s] : creases) {
      m.creases.push_back({edge.first, edge.second, s});
      key.insert(key.end(), {edge.first, edge.second, std::bit_cast<int32_t>(s)});
    }
    for (int i = 0; i < static_cast<int>(control_.size()); ++i)
      if (auto it = tags_.corners.find(control_[i]); it != tags_.corners.end()) {
        m.corners.push_back({i, it->second});
        key.insert(key.end(), {i, std::bit_cast<int32_t>(it->second)});
      }
    key.push_back(static_cast<int32_t>(m.corners.size()));
  }

  const ControlMesh& mesh_;
  const Far::TopologyLevel& level_;
  const std::vector<int>& offsets_;
  const GlobalTags& tags_;
  std::unordered_map<int, int> local_;
  std::vector<int> control_;
  std::vector<std::pair<int, int>> faces_;  // (global face, start)
};

struct KeyHash {
  size_t operator()(const std::vector<int32_t>& k) const {
    uint64_t h = 1469598103934665603ull;
    for (int32_t x : k) h = (h ^ static_cast<uint32_t>(x)) * 1099511628211ull;
    return static_cast<size_t>(h);
  }
};

// The faces a fragment owns; `centre`: a vertex patch's extraordinary vertex, -1 for a facet patch.
struct OwnedSet {
  std::vector<int> faces;
  int centre;
};

// Vertex patches for extraordinary vertices whose faces no earlier patch took; every other face
// (with a surface) a facet patch.
std::vector<OwnedSet> owned_face_sets(const ControlMesh& mesh, const Far::TopologyLevel& level, SubdivisionRule rule,
                                      const GlobalTags& tags, int& vertex_patches) {
  std::vector<OwnedSet> sets;
  std::vector<char> taken(mesh.face_sizes.size(), 0);
  vertex_patches = 0;
  for (int v = 0; v < level.GetNumVertices(); ++v) {
    if (!extraordinary(level, v, rule)) continue;
    Far::ConstIndexArray vf = level.GetVertexFaces(v);
    const bool free = std::none_of(vf.begin(), vf.end(), [&](int f) { return taken[f] || tags.hole[f]; });
    if (!free || vf.size() == 0) continue;
    sets.push_back({{vf.begin(), vf.end()}, v});
    for (int f : vf) taken[f] = 1;
    ++vertex_patches;
  }
  for (int f = 0; f < static_cast<int>(mesh.face_sizes.size()); ++f)
    if (!taken[f] && !tags.hole[f]) sets.push_back({{f}, -1});
  return sets;
}

// The rotations a fragment can be built in: a facet patch's face from each of its corners; a
// vertex patch's faces, each from the centre, the fan from each of its faces (Far orders a vertex's
// faces around it). Nets that differ only in where the global mesh happens to start its faces and
// fans then meet one rotation with the same key, and share a shape (and run eight to a call): the
// bunny's valence-5 and -7 vertex patches were each a shape of its own before.
struct Rotation {
  std::vector<int> faces, starts;
};

std::vector<Rotation> rotations_of(const OwnedSet& set, const ControlMesh& mesh, const std::vector<int>& offsets) {
  std::vector<Rotation> out;
  const int n = static_cast<int>(set.faces.size());
  if (set.centre < 0) {
    for (int s = 0; s < mesh.face_sizes[set.faces[0]]; ++s) out.push_back({set.faces, {s}});
    return out;
  }
  std::vector<int> starts(n);
  for (int k = 0; k < n; ++k) {
    const int f = set.faces[k];
    while (mesh.face_vertices[offsets[f] + starts[k]] != set.centre) ++starts[k];
  }
  for (int r = 0; r < n; ++r) {
    Rotation rot;
    for (int k = 0; k < n; ++k) rot.faces.push_back(set.faces[(r + k) % n]), rot.starts.push_back(starts[(r + k) % n]);
    out.push_back(std::move(rot));
  }
  return out;
}

}  // namespace

Partition partition_mesh(const ControlMesh& mesh, SubdivisionRule rule) {
  const auto refiner = make_refiner(mesh, rule);
  const Far::TopologyLevel& level = refiner->GetLevel(0);
  // A fragment net walks each vertex's faces as one fan; two fans meeting at a vertex (which the
  // harness's edge-manifold check lets through) have no such order.
  for (int v = 0; v < level.GetNumVertices(); ++v)
    if (level.IsVertexNonManifold(v) && level.GetVertexFaces(v).size() > 0)
      throw InputError(mesh.source, "vertex " + std::to_string(v) +
                                        " is non-manifold (its faces form more than one fan); mesh fragments need "
                                        "manifold vertices");
  const std::vector<int> offsets = face_offsets(mesh);
  const GlobalTags tags = global_tags(mesh);
  Partition p;
  const auto sets = owned_face_sets(mesh, level, rule, tags, p.vertex_patches);
  p.facet_patches = static_cast<int>(sets.size()) - p.vertex_patches;
  NetBuilder builder(mesh, level, offsets, tags);
  std::unordered_map<std::vector<int32_t>, int, KeyHash> shapes;
  std::vector<int32_t> key;
  std::vector<int32_t> best_key;
  for (const OwnedSet& set : sets) {
    // The rotation with the least key (the first of equals, so a facet patch with a symmetric net
    // keeps the global mesh's rotation).
    std::optional<std::pair<LocalNet, std::vector<int>>> best;
    Rotation chosen;
    for (Rotation& rot : rotations_of(set, mesh, offsets)) {
      auto built = builder.build(rot.faces, rot.starts, key);
      if (best && !(key < best_key)) continue;
      best = std::move(built), best_key = key, chosen = std::move(rot);
    }
    auto [it, fresh] = shapes.try_emplace(best_key, static_cast<int>(p.shapes.size()));
    if (fresh) p.shapes.push_back(std::move(best->first));
    p.fragments.push_back({std::move(chosen.faces), std::move(chosen.starts), std::move(best->second), it->second});
  }
  return p;
}

}  // namespace sdb::fragments
