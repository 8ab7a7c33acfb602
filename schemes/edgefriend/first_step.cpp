#include "schemes/edgefriend/first_step.h"

#include <opensubdiv/far/stencilTable.h>
#include <opensubdiv/far/stencilTableFactory.h>

#include <memory>

namespace sdb::edgefriend {

namespace Far = OpenSubdiv::Far;

StencilTable first_step(const Far::TopologyRefiner& level1, const Hierarchy& h) {
  Far::StencilTableFactory::Options o;
  o.generateOffsets = true;
  o.generateControlVerts = false;
  o.generateIntermediateLevels = false;
  o.maxLevel = 1;
  std::unique_ptr<const Far::StencilTable> far(Far::StencilTableFactory::Create(level1, o));
  StencilTable t;
  const int rows = far->GetNumStencils();
  for (int r = 0; r < rows; ++r) {
    const Far::Stencil s = far->GetStencil(r);
    for (int i = 0; i < s.GetSize(); ++i) t.source.push_back(uint32_t(s.GetVertexIndices()[i])), t.weight.push_back(s.GetWeights()[i]);
    t.begin.push_back(uint32_t(t.source.size()));
  }
  for (const std::vector<uint32_t>& loop : h.loops) {  // a ghost face's point: its corners' mean
    for (uint32_t v : loop) t.source.push_back(v), t.weight.push_back(1.0f / float(loop.size()));
    t.begin.push_back(uint32_t(t.source.size()));
  }
  return t;
}

void apply_stencils(const StencilTable& t, const Point3* src, Point3* dst, const uint32_t* out_index, uint32_t first,
                    uint32_t last) {
  for (uint32_t r = first; r < last; ++r) {
    const uint32_t to = out_index ? out_index[r] : r;
    if (to == kNone) continue;
    float x = 0, y = 0, z = 0;
    for (uint32_t i = t.begin[r]; i < t.begin[r + 1]; ++i) {
      const Point3& p = src[t.source[i]];
      const float w = t.weight[i];
      x = x + p[0] * w, y = y + p[1] * w, z = z + p[2] * w;
    }
    dst[to] = {x, y, z};
  }
}

}  // namespace sdb::edgefriend
