#include "harness/conformance/sweep_corpus.h"

#include <algorithm>
#include <map>

#include "datasets/manifest.h"
#include "harness/core/registry.h"
#include "harness/mesh/acceptance.h"
#include "harness/mesh/facts.h"
#include "harness/mesh/osd_topology.h"

namespace sdb::conformance {

std::vector<std::string> sweep_shapes(SubdivisionRule rule) {
  std::vector<std::string> names;
  const bool loop = rule == SubdivisionRule::Loop;
  for (const auto& e : list_meshes()) {
    if (e.kind != "corpus" || e.name.rfind("opensubdiv/", 0) != 0) continue;
    if (e.name.find(loop ? "/loop_" : "/catmark_") == std::string::npos) continue;
    names.push_back(e.name);
  }
  const std::vector<std::string> real = loop ? std::vector<std::string>{"stanford/bunny", "crane/spot_low_resolution",
                                                                         "pmp/icosahedron_subdiv"}
                                             : std::vector<std::string>{"crane/spot_control", "crane/blub_control",
                                                                         "pmp/fandisk_quads", "stein/sword_quad_dominant"};
  for (const std::string& n : real)
    if (corpus_has(n)) names.push_back(n);
  return names;
}

ControlMesh sweep_mesh(const std::string& name, SubdivisionRule rule, const std::string& scheme) {
  const ControlMesh m = load_mesh(name);
  make_refiner(m, rule);
  return accept_mesh(m, find_scheme(scheme)->info());
}

long boundary_edges(const ControlMesh& m) {
  std::map<std::pair<int, int>, int> edges;
  const std::vector<int> offsets = face_offsets(m);
  std::vector<char> hole(m.face_sizes.size(), 0);
  for (int f : m.holes) hole[f] = 1;
  for (int f = 0; f < num_faces(m); ++f)
    if (!hole[f])
    for (int i = offsets[f]; i < offsets[f + 1]; ++i) {
      const int a = m.face_vertices[i], b = m.face_vertices[i + 1 < offsets[f + 1] ? i + 1 : offsets[f]];
      ++edges[{std::min(a, b), std::max(a, b)}];
    }
  long n = 0;
  for (const auto& e : edges) n += e.second == 1;
  return n;
}

}  // namespace sdb::conformance
