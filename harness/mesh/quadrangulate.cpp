#include "quadrangulate.h"

#include "osd_topology.h"

namespace sdb {

ControlMesh quadrangulate(const ControlMesh& mesh) {
  auto refiner = make_refiner(mesh, SubdivisionRule::CatmullClark);
  OpenSubdiv::Far::TopologyRefiner::UniformOptions options(1);
  options.fullTopologyInLastLevel = true;
  refiner->RefineUniform(options);
  ControlMesh out = refined_level(*refiner, mesh, 1);
  out.source = mesh.source + " (one Catmull-Clark step)";
  return out;
}

}  // namespace sdb
