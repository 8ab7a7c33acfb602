#include "harness/mesh/quadrangulate.h"

#include "harness/mesh/osd_topology.h"

namespace sdb {

ControlMesh quadrangulate(const ControlMesh& mesh) {
  auto refiner = make_refiner(mesh, SubdivisionRule::CatmullClark);
  OpenSubdiv::Far::TopologyRefiner::UniformOptions options(1);
  options.fullTopologyInLastLevel = true;
  refiner->RefineUniform(options);
  // Same source: face lines still point at the input file (refined_level keeps them per parent).
  return refined_level(*refiner, mesh, 1);
}

}  // namespace sdb
