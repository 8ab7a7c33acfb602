#include "schemes/peers/limit_stencils.h"

#include <opensubdiv/far/patchMap.h>
#include <opensubdiv/far/patchTableFactory.h>
#include <opensubdiv/far/stencilTableFactory.h>
#include <opensubdiv/far/topologyRefiner.h>
#include <opensubdiv/osd/cpuEvaluator.h>

#include <algorithm>
#include <list>
#include <mutex>
#include <stdexcept>
#include <string>

#include "harness/core/content_hash.h"
#include "harness/mesh/facts.h"
#include "harness/mesh/osd_topology.h"
#include "harness/reference/surface_normal.h"
#include "harness/reference/uniform_coords.h"

namespace sdb {

namespace Far = OpenSubdiv::Far;
namespace Osd = OpenSubdiv::Osd;

namespace {

// The patch table LimitStencilTableFactory would make itself (its options, Gregory end caps),
// made here so that the vertices with no patch can be told apart before the table is made.
std::unique_ptr<const Far::PatchTable> limit_patches(const Far::TopologyRefiner& adaptive) {
  Far::PatchTableFactory::Options o;
  o.SetPatchPrecision<float>();
  o.includeBaseLevelIndices = true;
  o.SetEndCapType(Far::PatchTableFactory::Options::ENDCAP_GREGORY_BASIS);
  o.useInfSharpPatch = adaptive.GetAdaptiveOptions().useInfSharpPatch;
  return std::unique_ptr<const Far::PatchTable>(Far::PatchTableFactory::Create(adaptive, o));
}

}  // namespace

bool has_sharp_features(const ControlMesh& mesh) {
  return !mesh.creases.empty() || !mesh.corners.empty() || !mesh.holes.empty() || compute_facts(mesh).boundary_edges > 0;
}

SchemeInfo limit_stencil_info(SubdivisionRule rule) {
  SchemeInfo info;
  info.role = SchemeRole::Peer;
  // Limit patches in float (README.md): 1e-7 of the diagonal on smooth meshes, 4.8e-6 at
  // valence 360 (float sums), up to 6.6e-5 next to sharp features isolated to level 8. Normals
  // are not bounded: at an infinitely sharp corner the surface has none (135 degrees from the
  // reference's on catmark_cubes_infsharp).
  info.bound = {1e-4, -1};
  info.reference = rule;
  info.level_kind = LevelKind::Depth;
  info.default_levels = {1, 2, 3, 4};
  info.accepts.faces =
      rule == SubdivisionRule::Loop ? MeshRequirements::Faces::TrianglesOnly : MeshRequirements::Faces::Any;
  info.accepts.manifold = false;  // OpenSubdiv takes non-manifold topology
  info.accepts.creases = true;
  info.accepts.holes = true;
  return info;
}

namespace {

PreparedStencils make_limit_stencils(const ControlMesh& mesh, SubdivisionRule rule, int depth) {
  PreparedStencils prepared;
  auto made = std::make_shared<LimitStencils>();
  LimitStencils& out = *made;
  out.control_points = num_vertices(mesh);
  const auto uniform = make_refiner(mesh, rule);
  Far::TopologyRefiner::UniformOptions uniform_options(depth);
  uniform_options.fullTopologyInLastLevel = true;
  uniform->RefineUniform(uniform_options);
  prepared.topology.triangles = uniform_triangles(*uniform, depth);
  prepared.topology.coords = uniform_vertex_coords(*uniform, rule, depth);
  out.vertices = prepared.topology.coords.size();

  const auto adaptive = make_refiner(mesh, rule);
  Far::TopologyRefiner::AdaptiveOptions adaptive_options(std::max(depth + 1, has_sharp_features(mesh) ? 8 : 0));
  adaptive_options.useInfSharpPatch = true;
  adaptive->RefineAdaptive(adaptive_options);
  const auto patches = limit_patches(*adaptive);
  const Far::PatchMap patch_map(*patches);

  const std::vector<SurfaceCoord>& coords = prepared.topology.coords;
  std::vector<float> s, t;
  s.reserve(coords.size()), t.reserve(coords.size());
  for (uint32_t i = 0; i < coords.size(); ++i) {
    if (!patch_map.FindPatch(int(coords[i].face), coords[i].u, coords[i].v)) {
      out.refined_only.push_back(i);
      continue;
    }
    out.limit_vertices.push_back(i);
    s.push_back(coords[i].u), t.push_back(coords[i].v);
  }
  // One location array per vertex keeps stencil j for vertex limit_vertices[j].
  Far::LimitStencilTableFactory::LocationArrayVec locations(out.limit_vertices.size());
  for (size_t j = 0; j < locations.size(); ++j) {
    locations[j].ptexIdx = int(coords[out.limit_vertices[j]].face);
    locations[j].numLocations = 1;
    locations[j].s = &s[j];
    locations[j].t = &t[j];
  }
  Far::LimitStencilTableFactory::Options options;
  options.generate1stDerivatives = true;
  out.table.reset(Far::LimitStencilTableFactory::Create(*adaptive, locations, nullptr, patches.get(), options));
  const int stencils = out.table ? out.table->GetNumStencils() : 0;
  if (stencils != int(locations.size()))
    throw std::runtime_error("Far::LimitStencilTableFactory gave " + std::to_string(stencils) + " stencils for " +
                             std::to_string(locations.size()) + " vertices with a patch");
  if (!out.refined_only.empty()) {
    Far::StencilTableFactory::Options refined;
    refined.generateIntermediateLevels = false;
    refined.factorizeIntermediateLevels = true;
    refined.generateOffsets = true;
    out.refined.reset(Far::StencilTableFactory::Create(*uniform, refined));
  }
  prepared.stencils = std::move(made);
  return prepared;
}

// Everything make_limit_stencils reads of a mesh, as bytes: the counts, faces, tags and options,
// and the rule and depth; not the positions, the name or the source lines.
std::string topology_bytes(const ControlMesh& mesh, SubdivisionRule rule, int depth) {
  std::string bytes;
  const auto put = [&bytes](const void* data, size_t size) { bytes.append(static_cast<const char*>(data), size); };
  const auto put_vector = [&put](const auto& v) {
    const size_t n = v.size();
    put(&n, sizeof n);
    for (const auto& x : v) put(&x, sizeof x);
  };
  const int header[] = {int(rule), depth, num_vertices(mesh), int(mesh.boundary), int(mesh.crease_method),
                        int(mesh.triangle_rule)};
  put(header, sizeof header);
  put_vector(mesh.face_sizes);
  put_vector(mesh.face_vertices);
  put_vector(mesh.holes);
  const size_t creases = mesh.creases.size();  // tags field by field: their structs may hold padding
  put(&creases, sizeof creases);
  for (const EdgeCrease& c : mesh.creases)
    put(&c.v0, sizeof c.v0), put(&c.v1, sizeof c.v1), put(&c.sharpness, sizeof c.sharpness);
  const size_t corners = mesh.corners.size();
  put(&corners, sizeof corners);
  for (const VertexCorner& c : mesh.corners) put(&c.vertex, sizeof c.vertex), put(&c.sharpness, sizeof c.sharpness);
  return bytes;
}

size_t kept_bytes(const PreparedStencils& p, const std::string& key) {
  return p.stencils->bytes() + key.size() + p.topology.triangles.size() * sizeof(uint32_t) +
         p.topology.coords.size() * sizeof(SurfaceCoord);
}

// The tables kept, most recently used first; past kKeptStencilBytes the oldest are dropped.
struct KeptStencils {
  uint64_t hash;
  std::string key;
  PreparedStencils prepared;
  size_t bytes;
};
std::mutex g_kept_mutex;
std::list<KeptStencils> g_kept;

}  // namespace

size_t LimitStencils::bytes() const {
  size_t b = (limit_vertices.size() + refined_only.size()) * sizeof(uint32_t);
  if (table)
    b += (table->GetSizes().size() + table->GetOffsets().size() + table->GetControlIndices().size()) * sizeof(int) +
         (table->GetWeights().size() + table->GetDuWeights().size() + table->GetDvWeights().size()) * sizeof(float);
  if (refined)
    b += (refined->GetSizes().size() + refined->GetOffsets().size() + refined->GetControlIndices().size()) *
             sizeof(int) +
         refined->GetWeights().size() * sizeof(float);
  return b;
}

PreparedStencils limit_stencils(const ControlMesh& mesh, SubdivisionRule rule, int depth) {
  std::string key = topology_bytes(mesh, rule, depth);
  const uint64_t hash = fnv1a_64(key);
  {
    std::lock_guard<std::mutex> lock(g_kept_mutex);
    for (auto it = g_kept.begin(); it != g_kept.end(); ++it)
      if (it->hash == hash && it->key == key) {
        g_kept.splice(g_kept.begin(), g_kept, it);
        return it->prepared;  // the topology copied, the tables shared
      }
  }
  // Made outside the lock: another thread's tables for another mesh need not wait for these.
  PreparedStencils made = make_limit_stencils(mesh, rule, depth);
  const size_t bytes = kept_bytes(made, key);
  if (bytes > kKeptStencilBytes) return made;
  std::lock_guard<std::mutex> lock(g_kept_mutex);
  g_kept.push_front({hash, std::move(key), made, bytes});
  size_t total = 0;
  for (auto it = g_kept.begin(); it != g_kept.end();) {
    total += it->bytes;
    it = total > kKeptStencilBytes ? g_kept.erase(it) : std::next(it);
  }
  return made;
}

void evaluate_refined_only(const LimitStencils& s, const float* control, float* positions, float* du, float* dv) {
  if (s.refined_only.empty()) return;
  const Osd::BufferDescriptor desc(0, 3, 3);
  const Far::StencilTable& r = *s.refined;
  for (uint32_t v : s.refined_only) {
    // The evaluator writes stencil `start` to dst[0]: dst is this vertex's slot.
    Osd::CpuEvaluator::EvalStencils(control, desc, positions + 3 * size_t(v), desc, &r.GetSizes()[0], &r.GetOffsets()[0],
                                    &r.GetControlIndices()[0], &r.GetWeights()[0], int(v), int(v) + 1);
    std::fill(du + 3 * size_t(v), du + 3 * size_t(v) + 3, 0.0f);
    std::fill(dv + 3 * size_t(v), dv + 3 * size_t(v) + 3, 0.0f);
  }
}

void scatter_limit(const LimitStencils& s, const float* dense, float* out) {
  for (size_t j = 0; j < s.limit_vertices.size(); ++j)
    std::copy(dense + 3 * j, dense + 3 * j + 3, out + 3 * size_t(s.limit_vertices[j]));
}

void normals_from_tangents(const float* du, const float* dv, Point3* normals, size_t begin, size_t end) {
  for (size_t i = begin; i < end; ++i) normals[i] = unit_cross(du + 3 * i, dv + 3 * i);
}

}  // namespace sdb
