// The peer schemes every paper scheme is measured against, run through the same Scheme interface:
//   osd-uniform    Far uniform refinement to depth k, vertices projected to the limit with
//                  PrimvarRefiner::Limit, normals from the limit tangents (Catmull-Clark);
//   osd-uniform-loop  the same with Loop subdivision, for triangle schemes;
//   osd-bfr        Bfr surfaces evaluated on a rate-N tessellation of every face, border points
//                  shared per edge (Bfr tutorial style);
//   osd-bfr-loop   the same for Loop surfaces;
//   osd-stencil(-loop)    Far::LimitStencilTable at the vertices of depth-k refinement, evaluated
//                  by Osd::CpuEvaluator (cpu; cpu-mt on TBB ranges) or Osd::OmpEvaluator
//                  (cpu-mt with :omp=1): OpenSubdiv's fast path;
//   osd-glcompute(-loop)  the same tables on Osd::GLComputeEvaluator (opengl, headless EGL);
//   embree-subdiv  Embree's Catmull-Clark subdivision geometry evaluated with rtcInterpolate on
//                  the same rate-N layout (Embree's own limit evaluation, not ray sampling);
//   openmesh-cc, openmesh-loop  OpenMesh's uniform subdividers (the refined control mesh).
// One file per peer; scheme.cpp registers them (README.md).
#pragma once

#include <memory>
#include <vector>

#include "harness/core/scheme.h"

namespace sdb {

std::unique_ptr<Scheme> make_osd_uniform(SubdivisionRule rule);
std::unique_ptr<Scheme> make_osd_bfr(SubdivisionRule rule);
std::unique_ptr<Scheme> make_osd_stencil(SubdivisionRule rule);
std::unique_ptr<Scheme> make_osd_glcompute(SubdivisionRule rule);
std::unique_ptr<Scheme> make_embree_subdiv();
std::unique_ptr<Scheme> make_openmesh_subdivider(SubdivisionRule rule);

// osd-uniform, osd-uniform-loop, osd-bfr, osd-bfr-loop, osd-stencil, osd-stencil-loop,
// osd-glcompute, osd-glcompute-loop, embree-subdiv, openmesh-cc, openmesh-loop (in this order).
std::vector<std::unique_ptr<Scheme>> make_peer_schemes();

}  // namespace sdb
