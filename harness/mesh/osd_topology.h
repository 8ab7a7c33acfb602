// ControlMesh -> OpenSubdiv Far::TopologyRefiner, honouring creases, corners, holes and the
// boundary rule. Shared by quadrangulation and the reference surfaces.
#pragma once

#include <opensubdiv/far/topologyRefiner.h>

#include <memory>

#include "control_mesh.h"

namespace sdb {

enum class SubdivisionRule { CatmullClark, Loop };

OpenSubdiv::Sdc::Options sdc_options(const ControlMesh& mesh);

// Throws InputError with OpenSubdiv's own message when it refuses the topology.
std::unique_ptr<OpenSubdiv::Far::TopologyRefiner> make_refiner(const ControlMesh& mesh, SubdivisionRule rule);

// The refiner's level `level` as a ControlMesh (creases, corners and holes carried over), with
// positions interpolated by PrimvarRefiner. The refiner must have been refined uniformly to it.
ControlMesh refined_level(const OpenSubdiv::Far::TopologyRefiner& refiner, const ControlMesh& base, int level);

}  // namespace sdb
