// The output copy: a batch's limit entries, one lane per fragment (structure of arrays), into each
// fragment's block of the output (positions and normals as float3). For a fragment of one face
// the entries are in block order (ShapeTables::block_in_order) and the copy is a transpose.
#pragma once

#include <cstddef>

#include "harness/core/tessellation.h"
#include "schemes/fragments/kernel.h"

namespace sdb::fragments {

// For lanes l < lanes: pos[l][i] = position[i] (lane l) + origin, nrm[l][i] = normal[i] (lane l),
// i < n. The same bits however it runs (AVX where the CPU has it).
void write_blocks_in_order(const Lanes<kLanes>* position, const Lanes<kLanes>* normal, size_t n, const float origin[3],
                           Point3* const pos[kLanes], Point3* const nrm[kLanes], int lanes);

}  // namespace sdb::fragments
