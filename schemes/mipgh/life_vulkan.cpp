#include "schemes/mipgh/life_vulkan.h"

#include "harness/gpu/gpu.h"
#include "sdb_scheme_mipgh_shaders.h"

namespace sdb::mipgh {

namespace shaders = sdb_scheme_mipgh_shaders;

struct VulkanLife::Impl {
  struct Push {
    uint32_t nodes, lists;
  };
  std::shared_ptr<gpu::Context> ctx;  // outlives the objects below
  uint32_t nodes;
  gpu::Buffer words, state[2], staging_in, staging_out;
  std::shared_ptr<const gpu::ComputePipeline> pipeline;
  gpu::DescriptorSet sets[2];
  std::optional<gpu::Recording> generation[2], upload, download;
  int current = 0;  // the buffer holding the state

  Impl(const std::vector<uint32_t>& first, const std::vector<uint32_t>& neighbours)
      : ctx(gpu::shared_context()), nodes(uint32_t(first.size() - 1)) {
    gpu::Context& c = *ctx;
    std::vector<uint32_t> w = first;
    w.insert(w.end(), neighbours.begin(), neighbours.end());
    words = gpu::texel_table(c, w, "life's neighbour lists");
    const uint64_t bytes = std::max<uint64_t>(uint64_t(nodes) * 4, 16);
    gpu::check_texel_binding(c, nodes, "life's states");
    for (auto& s : state) s = gpu::Buffer::device(c, bytes, gpu::BufferUsage::UniformTexel | gpu::BufferUsage::StorageTexel, "life states");
    staging_in = gpu::Buffer::upload(c, bytes, "life states (staging)");
    staging_out = gpu::Buffer::readback(c, bytes, "life states (readback)");
    using gpu::Binding;
    pipeline = gpu::shared_compute_pipeline(
        c, gpu::ComputePipelineDesc{shaders::get("life.comp"),
                                    {Binding::UniformTexelBuffer, Binding::StorageTexelBuffer, Binding::UniformTexelBuffer},
                                    sizeof(Push), {}});
    const Push push{nodes, uint32_t(first.size())};
    for (int k = 0; k < 2; ++k) {
      sets[k] = gpu::DescriptorSet(*pipeline, {state[k].texels(VK_FORMAT_R32_SFLOAT), state[1 - k].texels(VK_FORMAT_R32_SFLOAT),
                                               words.texels(VK_FORMAT_R32_UINT)});
      generation[k] = ctx->record([&](gpu::Commands& cmd) {
        cmd.barrier(gpu::Stage::All, gpu::Stage::All);
        cmd.bind(*pipeline, sets[k]);
        cmd.push(push);
        cmd.dispatch(gpu::groups_for(nodes, 64, ctx->limits()));
      });
    }
    upload = ctx->record([&](gpu::Commands& cmd) { cmd.upload(staging_in, state[0]); });
    download_from(0);
  }

  void download_from(int k) {
    download = ctx->record([&](gpu::Commands& cmd) { cmd.download(state[k], staging_out); });
  }
};

VulkanLife::VulkanLife(const std::vector<uint32_t>& first, const std::vector<uint32_t>& neighbours)
    : impl_(std::make_unique<Impl>(first, neighbours)) {}
VulkanLife::~VulkanLife() = default;

void VulkanLife::upload(const std::vector<float>& state) {
  impl_->staging_in.write(state);
  impl_->ctx->submit(*impl_->upload);
  impl_->current = 0;
}

void VulkanLife::step() {
  impl_->ctx->submit(*impl_->generation[impl_->current]);
  impl_->current = 1 - impl_->current;
}

std::vector<float> VulkanLife::download() {
  impl_->download_from(impl_->current);
  impl_->ctx->submit(*impl_->download);
  return impl_->staging_out.read_as<float>(impl_->nodes);
}

}  // namespace sdb::mipgh
