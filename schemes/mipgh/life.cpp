#include "schemes/mipgh/life.h"

#include <memory>

#include "harness/mesh/osd_topology.h"
#include "schemes/mipgh/atlas.h"
#include "schemes/mipgh/life_vulkan.h"
#include "schemes/mipgh/lod.h"
#include "schemes/mipgh/mask_table.h"
#include "schemes/mipgh/processor.h"

namespace sdb::mipgh {

struct LifeOnMesh::Impl {
  DAtlas atlas;
  DLoD lod;
  EdgeTags tags;
  std::unique_ptr<MeshShader> shader;
  MeshProcessor processor;
  int depth;
  std::vector<V3> now, next;
  std::unique_ptr<VulkanLife> device;
  bool device_current = false;  // the device holds `now` (else the host's copy is newer)

  Impl(const ControlMesh& m, int d)
      : atlas(build_atlas(m)),
        lod(atlas, d),
        tags(build_tags(atlas, make_refiner(m, SubdivisionRule::CatmullClark)->GetLevel(0), sdc_options(m), d)),
        shader(make_shader(MeshRule::CatmullClark, sdc_options(m))),
        processor(atlas, lod, tags, *shader),
        depth(d),
        now(lod.layout(d).num_nodes, V3{0, 0, 0}),
        next(now.size()) {}
};

namespace {

// Every node's 1-disk at the depth as node lists: the live neighbours the shader counts.
void neighbour_lists(const MeshProcessor& p, int depth, uint32_t nodes, std::vector<uint32_t>& first,
                     std::vector<uint32_t>& lists) {
  const std::vector<V3> ids = node_ids(nodes);
  std::vector<std::vector<uint32_t>> of(nodes);
  p.adjustment_disks(depth, ids.data(), [&](uint32_t node, const VertexDisk& disk) {
    for (int i = 0; i < disk.edges; ++i) of[node].push_back(node_of(disk.e[i]));
    for (int i = 0; i < disk.faces; ++i) of[node].push_back(node_of(disk.d[i]));
  });
  first.assign(1, 0);
  for (const auto& l : of) lists.insert(lists.end(), l.begin(), l.end()), first.push_back(uint32_t(lists.size()));
}

}  // namespace

LifeOnMesh::LifeOnMesh(const ControlMesh& quads, int depth, Backend backend) : impl_(new Impl(quads, depth)) {
  if (backend != Backend::Vulkan) return;
  std::vector<uint32_t> first, lists;
  neighbour_lists(impl_->processor, depth, uint32_t(impl_->now.size()), first, lists);
  try {
    impl_->device = std::make_unique<VulkanLife>(first, lists);
  } catch (...) {
    delete impl_;
    throw;
  }
}
LifeOnMesh::~LifeOnMesh() { delete impl_; }

void LifeOnMesh::place(int facet, int top, int left, const std::vector<const char*>& pattern) {
  const int n = facet_side();
  const uint32_t* idx = impl_->lod.facet(impl_->depth, facet);
  for (size_t i = 0; i < pattern.size(); ++i)
    for (int j = 0; pattern[i][j]; ++j)
      if (pattern[i][j] == 'O') impl_->now[idx[(top + int(i)) * n + left + j]] = {1, 0, 0};
  impl_->device_current = false;
}

void LifeOnMesh::step() {
  if (Impl& m = *impl_; m.device) {
    if (!m.device_current) {
      std::vector<float> x(m.now.size());
      for (size_t i = 0; i < x.size(); ++i) x[i] = m.now[i].x;
      m.device->upload(x);
    }
    m.device->step();
    const std::vector<float> x = m.device->download();
    for (size_t i = 0; i < x.size(); ++i) m.now[i] = {x[i], 0, 0};
    m.device_current = true;
    return;
  }
  impl_->processor.adjust(impl_->depth, impl_->now.data(), impl_->next.data(), [](const VertexDisk& disk) {
    int alive = 0;
    for (int i = 0; i < disk.edges; ++i) alive += disk.e[i].x > 0.5f;
    for (int i = 0; i < disk.faces; ++i) alive += disk.d[i].x > 0.5f;  // a quad's corner across
    const bool was = disk.c.x > 0.5f;
    return V3{(alive == 3 || (was && alive == 2)) ? 1.0f : 0.0f, 0, 0};
  });
  impl_->now.swap(impl_->next);
}

const std::vector<V3>& LifeOnMesh::state() const { return impl_->now; }
int LifeOnMesh::facet_side() const { return impl_->lod.layout(impl_->depth).n; }
int LifeOnMesh::num_facets() const { return impl_->atlas.num_facets(); }

const std::vector<const char*>& pulsar() {
  static const std::vector<const char*> p = {
      "..OOO...OOO..", ".............", "O....O.O....O", "O....O.O....O", "O....O.O....O",
      "..OOO...OOO..", ".............", "..OOO...OOO..", "O....O.O....O", "O....O.O....O",
      "O....O.O....O", ".............", "..OOO...OOO.."};
  return p;
}

}  // namespace sdb::mipgh
