#include "harness/gpu/pipeline.h"

#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>

#include "harness/gpu/errors.h"

namespace sdb::gpu {

namespace {

VkDescriptorType descriptor_type(Binding b) {
  switch (b) {
    case Binding::StorageBuffer:
      return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    case Binding::UniformBuffer:
      return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    case Binding::UniformTexelBuffer:
      return VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
    case Binding::StorageTexelBuffer:
      return VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER;
  }
  throw std::logic_error("descriptor_type: unknown binding");
}

bool is_texel(Binding b) { return b == Binding::UniformTexelBuffer || b == Binding::StorageTexelBuffer; }

struct BindingRules {
  BufferUsage usage;
  const char* usage_name;
  uint64_t max_bytes, alignment;
};

BindingRules binding_rules(const DeviceLimits& l, Binding b, uint32_t texel_bytes) {
  switch (b) {
    case Binding::StorageBuffer:
      return {BufferUsage::Storage, "Storage", l.max_storage_buffer_range, l.min_storage_buffer_offset_alignment};
    case Binding::UniformBuffer:
      return {BufferUsage::Uniform, "Uniform", l.max_uniform_buffer_range, l.min_uniform_buffer_offset_alignment};
    case Binding::UniformTexelBuffer:
      return {BufferUsage::UniformTexel, "UniformTexel", l.max_texel_buffer_elements * texel_bytes,
              l.min_texel_buffer_offset_alignment};
    case Binding::StorageTexelBuffer:
      return {BufferUsage::StorageTexel, "StorageTexel", l.max_texel_buffer_elements * texel_bytes,
              l.min_texel_buffer_offset_alignment};
  }
  throw std::logic_error("binding_rules: unknown binding");
}

// Bytes per texel of the formats texel bindings take here (32-bit float and integer channels).
uint32_t texel_bytes(VkFormat format) {
  switch (format) {
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_R32_UINT:
    case VK_FORMAT_R32_SINT:
      return 4;
    case VK_FORMAT_R32G32_SFLOAT:
      return 8;
    case VK_FORMAT_R32G32B32A32_SFLOAT:
    case VK_FORMAT_R32G32B32A32_UINT:
    case VK_FORMAT_R32G32B32A32_SINT:
      return 16;
    default:
      return 0;
  }
}

// The range's size in bytes, after checking it against the binding's usage and the device's limits.
uint64_t checked_bytes(const Context& ctx, Binding binding, const BufferRange& r, const std::string& where) {
  const uint32_t texel = is_texel(binding) ? texel_bytes(r.texel_format) : 1;
  if (texel == 0) throw std::invalid_argument(where + ": a texel binding needs a 32-bit-channel texel_format");
  const BindingRules rules = binding_rules(ctx.limits(), binding, texel);
  if (!r.buffer || !*r.buffer) throw std::invalid_argument(where + ": no buffer");
  if (!has(r.buffer->usage(), rules.usage))
    throw std::invalid_argument(where + ": buffer '" + r.buffer->name() + "' was not made with usage " + rules.usage_name);
  const uint64_t bytes = r.bytes == VK_WHOLE_SIZE ? r.buffer->size() - r.offset : r.bytes;
  if (r.offset > r.buffer->size() || bytes > r.buffer->size() - r.offset)
    throw std::invalid_argument(where + ": range past the end of buffer '" + r.buffer->name() + "'");
  if (bytes > rules.max_bytes)
    throw std::invalid_argument(where + ": " + std::to_string(bytes) + " bytes of buffer '" + r.buffer->name() +
                                "' exceed the device's binding range of " + std::to_string(rules.max_bytes) +
                                " bytes; split it with plan_chunks()");
  if (r.offset % rules.alignment != 0)
    throw std::invalid_argument(where + ": offset " + std::to_string(r.offset) + " is not a multiple of " +
                                std::to_string(rules.alignment));
  if (bytes % texel != 0)
    throw std::invalid_argument(where + ": " + std::to_string(bytes) + " bytes are not whole texels of " +
                                std::to_string(texel) + " bytes");
  return bytes;
}

void count_descriptor(std::vector<VkDescriptorPoolSize>& sizes, VkDescriptorType type) {
  for (VkDescriptorPoolSize& s : sizes)
    if (s.type == type) {
      ++s.descriptorCount;
      return;
    }
  sizes.push_back({type, 1});
}

VkBufferView make_view(const Context& ctx, const BufferRange& r, uint64_t bytes) {
  VkBufferViewCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO};
  info.buffer = r.buffer->handle();
  info.format = r.texel_format;
  info.offset = r.offset;
  info.range = bytes;
  VkBufferView view = VK_NULL_HANDLE;
  check(ctx.vk().vkCreateBufferView(ctx.device(), &info, nullptr, &view), "vkCreateBufferView",
        "creating a texel view of buffer '" + r.buffer->name() + "'");
  return view;
}

std::optional<std::string> push_constants_unsupported(const Context& ctx, uint32_t bytes) {
  if (bytes > ctx.limits().max_push_constants_size)
    return ctx.info().name + " allows " + std::to_string(ctx.limits().max_push_constants_size) +
           " bytes of push constants, the pipeline wants " + std::to_string(bytes);
  return std::nullopt;
}

// Shader modules live only while a pipeline is created.
class ShaderModules {
 public:
  explicit ShaderModules(const Context& ctx) : ctx_(ctx) {}
  ~ShaderModules() {
    for (VkShaderModule m : modules_) ctx_.vk().vkDestroyShaderModule(ctx_.device(), m, nullptr);
  }
  ShaderModules(const ShaderModules&) = delete;
  ShaderModules& operator=(const ShaderModules&) = delete;

  VkShaderModule make(const Spirv& spirv) {
    if (spirv.words.empty()) throw std::invalid_argument("shader '" + std::string(spirv.name) + "' has no SPIR-V");
    VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    info.codeSize = spirv.words.size_bytes();
    info.pCode = spirv.words.data();
    VkShaderModule module = VK_NULL_HANDLE;
    check(ctx_.vk().vkCreateShaderModule(ctx_.device(), &info, nullptr, &module), "vkCreateShaderModule",
          "loading shader " + std::string(spirv.name));
    modules_.push_back(module);
    return module;
  }

 private:
  const Context& ctx_;
  std::vector<VkShaderModule> modules_;
};

// Every stage reads the same constants; a stage that does not declare an id ignores it.
struct Specialization {
  std::vector<VkSpecializationMapEntry> entries;
  std::vector<uint32_t> values;
  VkSpecializationInfo info{};

  explicit Specialization(const std::vector<SpecConstant>& constants) {
    for (size_t i = 0; i < constants.size(); ++i) {
      entries.push_back({constants[i].id, static_cast<uint32_t>(i * sizeof(uint32_t)), sizeof(uint32_t)});
      values.push_back(constants[i].value);
    }
    info.mapEntryCount = static_cast<uint32_t>(entries.size());
    info.pMapEntries = entries.data();
    info.dataSize = values.size() * sizeof(uint32_t);
    info.pData = values.data();
  }
  const VkSpecializationInfo* get() const { return entries.empty() ? nullptr : &info; }
};

VkPrimitiveTopology vk_topology(Topology t) {
  switch (t) {
    case Topology::TriangleList: return VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    case Topology::TriangleStrip: return VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP;
    case Topology::LineList: return VK_PRIMITIVE_TOPOLOGY_LINE_LIST;
    case Topology::LineListWithAdjacency: return VK_PRIMITIVE_TOPOLOGY_LINE_LIST_WITH_ADJACENCY;
    case Topology::PointList: return VK_PRIMITIVE_TOPOLOGY_POINT_LIST;
    case Topology::PatchList: return VK_PRIMITIVE_TOPOLOGY_PATCH_LIST;
  }
  return VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
}

VkCullModeFlags vk_cull(CullMode c) {
  switch (c) {
    case CullMode::None: return VK_CULL_MODE_NONE;
    case CullMode::Back: return VK_CULL_MODE_BACK_BIT;
    case CullMode::Front: return VK_CULL_MODE_FRONT_BIT;
  }
  return VK_CULL_MODE_NONE;
}

void check_graphics_desc(const GraphicsPipelineDesc& d) {
  if (d.tess_control.has_value() != d.tess_evaluation.has_value())
    throw std::invalid_argument("graphics pipeline: give both tessellation stages or neither");
  const bool tess = d.tess_control.has_value();
  if (tess != (d.topology == Topology::PatchList))
    throw std::invalid_argument("graphics pipeline: tessellation stages go with Topology::PatchList and only with it");
  for (const VertexAttribute& a : d.vertex_attributes)
    if (a.binding >= d.vertex_bindings.size())
      throw std::invalid_argument("graphics pipeline: vertex attribute at location " + std::to_string(a.location) +
                                  " names vertex binding " + std::to_string(a.binding) + ", which is not declared");
}

}  // namespace

std::optional<std::string> unsupported(const Context& ctx, const ComputePipelineDesc& desc) {
  return push_constants_unsupported(ctx, desc.push_constant_bytes);
}

std::optional<std::string> unsupported(const Context& ctx, const GraphicsPipelineDesc& desc) {
  const DeviceFeatures& f = ctx.features();
  const std::string& name = ctx.info().name;
  if (desc.geometry && !f.geometry_shader) return name + " lacks geometry shaders (geometryShader)";
  if (desc.tess_control && !f.tessellation_shader) return name + " lacks tessellation shaders (tessellationShader)";
  if (desc.topology == Topology::PatchList &&
      (desc.patch_control_points == 0 || desc.patch_control_points > ctx.limits().max_tessellation_patch_size))
    return name + " takes patches of 1 to " + std::to_string(ctx.limits().max_tessellation_patch_size) +
           " control points, the pipeline wants " + std::to_string(desc.patch_control_points);
  if (desc.wireframe && !f.fill_mode_non_solid) return name + " lacks wireframe rendering (fillModeNonSolid)";
  return push_constants_unsupported(ctx, desc.push_constant_bytes);
}

Pipeline::Pipeline(Pipeline&& other) noexcept { *this = std::move(other); }

Pipeline& Pipeline::operator=(Pipeline&& other) noexcept {
  if (this != &other) {
    release();
    ctx_ = std::exchange(other.ctx_, nullptr);
    pipeline_ = std::exchange(other.pipeline_, VK_NULL_HANDLE);
    layout_ = std::exchange(other.layout_, VK_NULL_HANDLE);
    set_layout_ = std::exchange(other.set_layout_, VK_NULL_HANDLE);
    bind_point_ = other.bind_point_;
    stages_ = other.stages_;
    bindings_ = std::move(other.bindings_);
    push_constant_bytes_ = other.push_constant_bytes_;
  }
  return *this;
}

Pipeline::~Pipeline() { release(); }

void Pipeline::release() {
  if (!ctx_) return;
  const Vk& vk = ctx_->vk();
  if (pipeline_) vk.vkDestroyPipeline(ctx_->device(), pipeline_, nullptr);
  if (layout_) vk.vkDestroyPipelineLayout(ctx_->device(), layout_, nullptr);
  if (set_layout_) vk.vkDestroyDescriptorSetLayout(ctx_->device(), set_layout_, nullptr);
  pipeline_ = VK_NULL_HANDLE;
  layout_ = VK_NULL_HANDLE;
  set_layout_ = VK_NULL_HANDLE;
  ctx_ = nullptr;
}

void Pipeline::create_layout(Context& ctx, VkPipelineBindPoint point, VkShaderStageFlags stages,
                             const std::vector<Binding>& bindings, uint32_t push_constant_bytes) {
  ctx_ = &ctx;
  bind_point_ = point;
  stages_ = stages;
  bindings_ = bindings;
  push_constant_bytes_ = push_constant_bytes;
  const Vk& vk = ctx.vk();
  std::vector<VkDescriptorSetLayoutBinding> entries;
  for (uint32_t i = 0; i < bindings.size(); ++i)
    entries.push_back({i, descriptor_type(bindings[i]), 1, stages, nullptr});
  VkDescriptorSetLayoutCreateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  set_info.bindingCount = static_cast<uint32_t>(entries.size());
  set_info.pBindings = entries.data();
  check(vk.vkCreateDescriptorSetLayout(ctx.device(), &set_info, nullptr, &set_layout_), "vkCreateDescriptorSetLayout",
        "creating a pipeline's descriptor set layout");
  VkPushConstantRange push{stages, 0, push_constant_bytes};
  VkPipelineLayoutCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  info.setLayoutCount = 1;
  info.pSetLayouts = &set_layout_;
  info.pushConstantRangeCount = push_constant_bytes > 0 ? 1 : 0;
  info.pPushConstantRanges = &push;
  check(vk.vkCreatePipelineLayout(ctx.device(), &info, nullptr, &layout_), "vkCreatePipelineLayout",
        "creating a pipeline layout");
}

ComputePipeline::ComputePipeline(Context& ctx, const ComputePipelineDesc& desc) {
  if (auto why = unsupported(ctx, desc)) throw Unsupported(*why);
  create_layout(ctx, VK_PIPELINE_BIND_POINT_COMPUTE, VK_SHADER_STAGE_COMPUTE_BIT, desc.bindings,
                desc.push_constant_bytes);
  ShaderModules modules(ctx);
  Specialization spec(desc.constants);
  VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  info.stage.module = modules.make(desc.shader);
  info.stage.pName = "main";
  info.stage.pSpecializationInfo = spec.get();
  info.layout = layout_;
  check(ctx.vk().vkCreateComputePipelines(ctx.device(), ctx.pipeline_cache(), 1, &info, nullptr, &pipeline_),
        "vkCreateComputePipelines", "creating compute pipeline " + std::string(desc.shader.name));
}

namespace {

// What makes two compute pipelines the same: the embedded shader (its words are static, so their
// address names them), the bindings, the push constants' size and the specialization.
std::string pipeline_key(const ComputePipelineDesc& desc) {
  std::string key = std::string(desc.shader.name) + "@" +
                    std::to_string(reinterpret_cast<uintptr_t>(desc.shader.words.data())) + ":" +
                    std::to_string(desc.shader.words.size()) + " b";
  for (Binding b : desc.bindings) key += std::to_string(static_cast<int>(b));
  key += " p" + std::to_string(desc.push_constant_bytes);
  for (const SpecConstant& c : desc.constants) key += " " + std::to_string(c.id) + "=" + std::to_string(c.value);
  return key;
}

}  // namespace

std::shared_ptr<const ComputePipeline> shared_compute_pipeline(Context& ctx, const ComputePipelineDesc& desc) {
  return std::static_pointer_cast<const ComputePipeline>(
      ctx.shared_pipeline(pipeline_key(desc), [&] { return std::make_shared<const ComputePipeline>(ctx, desc); }));
}

GraphicsPipeline::GraphicsPipeline(Context& ctx, const GraphicsPipelineDesc& desc) {
  check_graphics_desc(desc);
  if (auto why = unsupported(ctx, desc)) throw Unsupported(*why);
  ShaderModules modules(ctx);
  Specialization spec(desc.constants);
  std::vector<VkPipelineShaderStageCreateInfo> stages;
  VkShaderStageFlags stage_flags = 0;
  auto add_stage = [&](VkShaderStageFlagBits stage, const Spirv& spirv) {
    VkPipelineShaderStageCreateInfo s{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    s.stage = stage;
    s.module = modules.make(spirv);
    s.pName = "main";
    s.pSpecializationInfo = spec.get();
    stages.push_back(s);
    stage_flags |= stage;
  };
  add_stage(VK_SHADER_STAGE_VERTEX_BIT, desc.vertex);
  if (desc.tess_control) add_stage(VK_SHADER_STAGE_TESSELLATION_CONTROL_BIT, *desc.tess_control);
  if (desc.tess_evaluation) add_stage(VK_SHADER_STAGE_TESSELLATION_EVALUATION_BIT, *desc.tess_evaluation);
  if (desc.geometry) add_stage(VK_SHADER_STAGE_GEOMETRY_BIT, *desc.geometry);
  add_stage(VK_SHADER_STAGE_FRAGMENT_BIT, desc.fragment);
  create_layout(ctx, VK_PIPELINE_BIND_POINT_GRAPHICS, stage_flags, desc.bindings, desc.push_constant_bytes);

  std::vector<VkVertexInputBindingDescription> vertex_bindings;
  for (uint32_t i = 0; i < desc.vertex_bindings.size(); ++i)
    vertex_bindings.push_back({i, desc.vertex_bindings[i].stride,
                               desc.vertex_bindings[i].per_instance ? VK_VERTEX_INPUT_RATE_INSTANCE
                                                                    : VK_VERTEX_INPUT_RATE_VERTEX});
  std::vector<VkVertexInputAttributeDescription> attributes;
  for (const VertexAttribute& a : desc.vertex_attributes) attributes.push_back({a.location, a.binding, a.format, a.offset});
  VkPipelineVertexInputStateCreateInfo vertex_input{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  vertex_input.vertexBindingDescriptionCount = static_cast<uint32_t>(vertex_bindings.size());
  vertex_input.pVertexBindingDescriptions = vertex_bindings.data();
  vertex_input.vertexAttributeDescriptionCount = static_cast<uint32_t>(attributes.size());
  vertex_input.pVertexAttributeDescriptions = attributes.data();

  VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  assembly.topology = vk_topology(desc.topology);
  VkPipelineTessellationStateCreateInfo tessellation{VK_STRUCTURE_TYPE_PIPELINE_TESSELLATION_STATE_CREATE_INFO};
  tessellation.patchControlPoints = desc.patch_control_points;
  VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  viewport.viewportCount = 1;
  viewport.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  raster.polygonMode = desc.wireframe ? VK_POLYGON_MODE_LINE : VK_POLYGON_MODE_FILL;
  raster.cullMode = vk_cull(desc.cull);
  raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  raster.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  depth.depthTestEnable = desc.depth_test;
  depth.depthWriteEnable = desc.depth_test;
  depth.depthCompareOp = VK_COMPARE_OP_LESS;
  VkPipelineColorBlendAttachmentState blend_attachment{};
  blend_attachment.colorWriteMask =
      VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
  VkPipelineColorBlendStateCreateInfo blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  blend.attachmentCount = 1;
  blend.pAttachments = &blend_attachment;
  const VkDynamicState dynamic_states[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dynamic.dynamicStateCount = 2;
  dynamic.pDynamicStates = dynamic_states;

  VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  info.stageCount = static_cast<uint32_t>(stages.size());
  info.pStages = stages.data();
  info.pVertexInputState = &vertex_input;
  info.pInputAssemblyState = &assembly;
  info.pTessellationState = desc.topology == Topology::PatchList ? &tessellation : nullptr;
  info.pViewportState = &viewport;
  info.pRasterizationState = &raster;
  info.pMultisampleState = &multisample;
  info.pDepthStencilState = &depth;
  info.pColorBlendState = &blend;
  info.pDynamicState = &dynamic;
  info.layout = layout_;
  info.renderPass = ctx.offscreen_render_pass();
  info.subpass = 0;
  check(ctx.vk().vkCreateGraphicsPipelines(ctx.device(), ctx.pipeline_cache(), 1, &info, nullptr, &pipeline_),
        "vkCreateGraphicsPipelines",
        "creating graphics pipeline " + std::string(desc.vertex.name) + " + " + std::string(desc.fragment.name));
}

DescriptorSet::DescriptorSet(const Pipeline& pipeline, const std::vector<BufferRange>& ranges)
    : ctx_(&pipeline.context()) {
  const std::vector<Binding>& bindings = pipeline.bindings();
  if (ranges.size() != bindings.size())
    throw std::invalid_argument("descriptor set: the pipeline has " + std::to_string(bindings.size()) +
                                " bindings, " + std::to_string(ranges.size()) + " buffer ranges were given");
  std::vector<VkDescriptorBufferInfo> infos;
  std::vector<VkDescriptorPoolSize> sizes;
  for (size_t i = 0; i < ranges.size(); ++i) {
    const uint64_t bytes = checked_bytes(*ctx_, bindings[i], ranges[i], "binding " + std::to_string(i));
    infos.push_back({ranges[i].buffer->handle(), ranges[i].offset, bytes});
    count_descriptor(sizes, descriptor_type(bindings[i]));
  }
  if (infos.empty()) return;  // nothing to bind; Commands::bind skips an empty set
  try {
    allocate(pipeline, sizes);
    for (size_t i = 0; i < ranges.size(); ++i)
      if (is_texel(bindings[i])) views_.push_back(make_view(*ctx_, ranges[i], infos[i].range));
  } catch (...) {
    release();
    throw;
  }
  std::vector<VkWriteDescriptorSet> writes;
  for (uint32_t i = 0, view = 0; i < infos.size(); ++i) {
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstSet = set_;
    w.dstBinding = i;
    w.descriptorCount = 1;
    w.descriptorType = descriptor_type(bindings[i]);
    if (is_texel(bindings[i]))
      w.pTexelBufferView = &views_[view++];
    else
      w.pBufferInfo = &infos[i];
    writes.push_back(w);
  }
  ctx_->vk().vkUpdateDescriptorSets(ctx_->device(), static_cast<uint32_t>(writes.size()), writes.data(), 0, nullptr);
}

void DescriptorSet::allocate(const Pipeline& pipeline, const std::vector<VkDescriptorPoolSize>& sizes) {
  const Vk& vk = ctx_->vk();
  VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pool_info.maxSets = 1;
  pool_info.poolSizeCount = static_cast<uint32_t>(sizes.size());
  pool_info.pPoolSizes = sizes.data();
  check(vk.vkCreateDescriptorPool(ctx_->device(), &pool_info, nullptr, &pool_), "vkCreateDescriptorPool",
        "creating a descriptor pool");
  VkDescriptorSetLayout layout = pipeline.set_layout();
  VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  alloc.descriptorPool = pool_;
  alloc.descriptorSetCount = 1;
  alloc.pSetLayouts = &layout;
  check(vk.vkAllocateDescriptorSets(ctx_->device(), &alloc, &set_), "vkAllocateDescriptorSets",
        "allocating a descriptor set");
}

DescriptorSet::DescriptorSet(DescriptorSet&& other) noexcept { *this = std::move(other); }

DescriptorSet& DescriptorSet::operator=(DescriptorSet&& other) noexcept {
  if (this != &other) {
    release();
    ctx_ = std::exchange(other.ctx_, nullptr);
    pool_ = std::exchange(other.pool_, VK_NULL_HANDLE);
    set_ = std::exchange(other.set_, VK_NULL_HANDLE);
    views_ = std::exchange(other.views_, {});
  }
  return *this;
}

DescriptorSet::~DescriptorSet() { release(); }

void DescriptorSet::release() {
  // Destroying the pool frees its set.
  if (ctx_ && pool_) ctx_->vk().vkDestroyDescriptorPool(ctx_->device(), pool_, nullptr);
  for (VkBufferView view : views_)
    if (ctx_) ctx_->vk().vkDestroyBufferView(ctx_->device(), view, nullptr);
  views_.clear();
  pool_ = VK_NULL_HANDLE;
  set_ = VK_NULL_HANDLE;
  ctx_ = nullptr;
}

}  // namespace sdb::gpu
