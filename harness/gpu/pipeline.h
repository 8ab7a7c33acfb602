// Pipelines (compute and graphics) and the descriptor sets that feed them.
//
// One descriptor set (set 0) per pipeline; binding i is bindings[i], a storage or uniform
// buffer. Push constants are one block of push_constant_bytes from offset 0, visible to every
// stage of the pipeline. Specialization constants are 32-bit values by constant_id.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "harness/gpu/buffer.h"
#include "harness/gpu/context.h"
#include "harness/gpu/spirv.h"

namespace sdb::gpu {

// Texel buffers are read (texelFetch on a samplerBuffer) or written (imageStore on an
// imageBuffer) through a view in the BufferRange's texel_format. On lavapipe they are the fast
// path: a storage buffer's loads and stores go lane by lane with a branch each, a texel fetch is
// one vector gather (README.md, "Memory access on lavapipe").
enum class Binding { StorageBuffer, UniformBuffer, UniformTexelBuffer, StorageTexelBuffer };

struct SpecConstant {
  uint32_t id = 0;  // layout(constant_id = id)
  uint32_t value = 0;  // the bits of an int, uint, float or bool (0/1)
};

struct ComputePipelineDesc {
  Spirv shader;
  std::vector<Binding> bindings;
  uint32_t push_constant_bytes = 0;
  std::vector<SpecConstant> constants;
};

// LineListWithAdjacency: four vertices per primitive, what a geometry shader that takes a quad reads.
enum class Topology { TriangleList, TriangleStrip, LineList, LineListWithAdjacency, PointList, PatchList };
enum class CullMode { None, Back, Front };  // front faces are counter-clockwise

struct VertexBinding {  // vertex buffer binding = index in GraphicsPipelineDesc::vertex_bindings
  uint32_t stride = 0;
  bool per_instance = false;
};

struct VertexAttribute {
  uint32_t location = 0;
  uint32_t binding = 0;
  VkFormat format = VK_FORMAT_R32G32B32_SFLOAT;
  uint32_t offset = 0;
};

struct GraphicsPipelineDesc {
  Spirv vertex;
  Spirv fragment;
  std::optional<Spirv> tess_control;  // both tessellation stages or neither
  std::optional<Spirv> tess_evaluation;
  std::optional<Spirv> geometry;
  std::vector<VertexBinding> vertex_bindings;
  std::vector<VertexAttribute> vertex_attributes;
  Topology topology = Topology::TriangleList;
  uint32_t patch_control_points = 0;  // Topology::PatchList
  std::vector<Binding> bindings;
  uint32_t push_constant_bytes = 0;
  std::vector<SpecConstant> constants;  // given to every stage
  bool depth_test = true;  // test and write, less-than
  CullMode cull = CullMode::None;
  bool wireframe = false;  // needs fillModeNonSolid
};

// Why `ctx`'s device cannot build this pipeline (a missing feature or limit), or nullopt.
// Schemes call these from Scheme::unsupported(); the constructors throw Unsupported with the same text.
std::optional<std::string> unsupported(const Context& ctx, const ComputePipelineDesc& desc);
std::optional<std::string> unsupported(const Context& ctx, const GraphicsPipelineDesc& desc);

class Pipeline {
 public:
  Pipeline(const Pipeline&) = delete;
  Pipeline& operator=(const Pipeline&) = delete;
  Pipeline(Pipeline&& other) noexcept;
  Pipeline& operator=(Pipeline&& other) noexcept;
  ~Pipeline();

  Context& context() const { return *ctx_; }
  VkPipeline handle() const { return pipeline_; }
  VkPipelineLayout layout() const { return layout_; }
  VkDescriptorSetLayout set_layout() const { return set_layout_; }
  VkPipelineBindPoint bind_point() const { return bind_point_; }
  VkShaderStageFlags stages() const { return stages_; }  // push constants and bindings are visible here
  const std::vector<Binding>& bindings() const { return bindings_; }
  uint32_t push_constant_bytes() const { return push_constant_bytes_; }

 protected:
  Pipeline() = default;
  void create_layout(Context& ctx, VkPipelineBindPoint point, VkShaderStageFlags stages,
                     const std::vector<Binding>& bindings, uint32_t push_constant_bytes);
  void release();

  Context* ctx_ = nullptr;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
  VkPipelineBindPoint bind_point_ = VK_PIPELINE_BIND_POINT_COMPUTE;
  VkShaderStageFlags stages_ = 0;
  std::vector<Binding> bindings_;
  uint32_t push_constant_bytes_ = 0;
};

class ComputePipeline : public Pipeline {
 public:
  // Throws Unsupported, VulkanError.
  ComputePipeline(Context& ctx, const ComputePipelineDesc& desc);
};

// The context's compute pipeline for `desc`: made at the first request, shared by every later
// one with the same shader, bindings, push constant size and specialization. lavapipe compiles a
// pipeline's shader with LLVM when it first runs (tens of milliseconds), so evaluations that make
// the same pipelines again (a test's sweep, a benchmark's setups) compile each once. Throws as
// the constructor does.
std::shared_ptr<const ComputePipeline> shared_compute_pipeline(Context& ctx, const ComputePipelineDesc& desc);

class GraphicsPipeline : public Pipeline {
 public:
  // Made against ctx.offscreen_render_pass(); viewport and scissor are dynamic (set by
  // RenderTarget::begin). Throws Unsupported, std::invalid_argument, VulkanError.
  GraphicsPipeline(Context& ctx, const GraphicsPipelineDesc& desc);
};

// The buffers of one pipeline's set 0: ranges[i] goes to binding i. Each range must fit the
// device's maxStorageBufferRange / maxUniformBufferRange and start at a multiple of its offset
// alignment (std::invalid_argument says which binding does not); plan large outputs with chunks.h.
// Owns its small descriptor pool. The buffers must outlive the set's use.
class DescriptorSet {
 public:
  DescriptorSet() = default;
  DescriptorSet(const Pipeline& pipeline, const std::vector<BufferRange>& ranges);
  DescriptorSet(const DescriptorSet&) = delete;
  DescriptorSet& operator=(const DescriptorSet&) = delete;
  DescriptorSet(DescriptorSet&& other) noexcept;
  DescriptorSet& operator=(DescriptorSet&& other) noexcept;
  ~DescriptorSet();

  VkDescriptorSet handle() const { return set_; }

 private:
  void allocate(const Pipeline& pipeline, const std::vector<VkDescriptorPoolSize>& sizes);
  void release();
  Context* ctx_ = nullptr;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  std::vector<VkBufferView> views_;  // of the texel bindings, in binding order
};

}  // namespace sdb::gpu
