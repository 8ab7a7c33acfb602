// The Vulkan backend, all of it: see README.md in this folder.
#pragma once

#include "harness/gpu/buffer.h"        // Buffer, MemoryKind, BufferUsage, upload/download
#include "harness/gpu/chunks.h"        // plan_chunks, groups_for
#include "harness/gpu/commands.h"      // Commands, Recording, Stage, Groups
#include "harness/gpu/context.h"       // Context, shared_context
#include "harness/gpu/device_info.h"   // probe, DeviceInfo, DeviceLimits
#include "harness/gpu/errors.h"        // Unavailable, Unsupported, VulkanError
#include "harness/gpu/heaps.h"         // MemoryNeed, check_memory
#include "harness/gpu/image.h"         // Image, write_png
#include "harness/gpu/mesh_renderer.h" // MeshRenderer, Camera, render_image
#include "harness/gpu/pipeline.h"      // ComputePipeline, GraphicsPipeline, DescriptorSet
#include "harness/gpu/readback.h"      // OutputReadback
#include "harness/gpu/render_target.h" // RenderTarget
#include "harness/gpu/spirv.h"         // Spirv
#include "harness/gpu/timer.h"         // GpuTimer, PassKind
