// The c-patch paper's tables (TABLES.md): ni2008-table4 and ni2008-table5 (frames per second of the
// 2-pass and 1-pass variants in render mode, fps.cpp) and ni2008-fig12 (deviation from the
// Catmull-Clark limit with heat maps, fig12.cpp).
#include "harness/core/paper_table.h"
#include "harness/core/registry.h"
#include "harness/gpu/gpu.h"
#include "harness/mesh/facts.h"
#include "schemes/cpatch/paper/paper.h"

namespace sdb {

std::vector<PaperTable> cpatch_paper_tables() {
  return {{"ni2008-table4", "GPU Smoothing of Quad Meshes, Table 4: 2-pass frames per second", cpatch::run_table4},
          {"ni2008-table5", "GPU Smoothing of Quad Meshes, Table 5: 1-pass (geometry shader) frames per second",
           cpatch::run_table5},
          {"ni2008-fig12", "GPU Smoothing of Quad Meshes, Figure 12: c-patch surface against the Catmull-Clark limit",
           cpatch::run_fig12}};
}

// The paper tables register here, with the experiments (sdb_scheme_cpatch_paper), not with the
// algorithm: the plug-in library links no measurement (cmake/Schemes.cmake).
SDB_REGISTER_PAPER_TABLES(cpatch, cpatch_paper_tables);

namespace cpatch {

std::string mesh_shape(MeasureContext& context, const std::string& mesh, const ControlMesh& quads) {
  const MeshFacts f = compute_facts(context.mesh(mesh));
  std::string shape = "(" + std::to_string(f.vertices) + ", " + std::to_string(f.faces) + ", " +
                      fixed(100 * f.extraordinary_quad_fraction, 0) + "%)";
  if (!f.all_quads) shape += ", " + std::to_string(num_faces(quads)) + " quads after one Catmull-Clark step";
  return shape;
}

}  // namespace cpatch
}  // namespace sdb
