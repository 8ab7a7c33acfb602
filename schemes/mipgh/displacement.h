// Normal displacement (Figure 22's last shader): after the limit projection, every node of the
// last level moves along its unit normal by scale * d(u, v), d an image's first channel in [0, 1]
// read with OpenImageIO, (u, v) the node's texture coordinates, a chart-morphic attribute
// (chart.h) the mesh shader reads by hashing; with unit charts (the figure's) every D-facet covers
// the whole image. An adjustment without refinement (Figure 24's bypassed case): a node shared by
// D-facets is displaced once, with the first D-facet's coordinates, so the surface stays
// watertight by construction; an image that vanishes at its border (the default, bumps) is also
// continuous across D-facets.
#pragma once

#include <string>
#include <vector>

#include "harness/core/tessellation.h"
#include "schemes/mipgh/atlas.h"
#include "schemes/mipgh/chart.h"
#include "schemes/mipgh/lod.h"

namespace sdb::mipgh {

struct DisplacementMap {
  int width = 0, height = 0;
  std::vector<float> values;  // row-major, [0, 1]
  float sample(float u, float v) const;  // bilinear, (0, 0) the first pixel's centre ... (1, 1) the last's
};

// Throws InputError naming the file when it is missing or OpenImageIO cannot read it.
DisplacementMap read_displacement(const std::string& path);
// One bump in [0, 1], zero along the border: sin(pi u) sin(pi v).
DisplacementMap bumps(int size);

// Moves t's positions (level `depth` of lod, one per node) along t's normals, reading the map at
// `coords` (of that level).
void displace_along_normals(const DAtlas& atlas, const DLoD& lod, int depth, const ChartAttribute& coords,
                            const DisplacementMap& map, float scale, Tessellation& t);

}  // namespace sdb::mipgh
