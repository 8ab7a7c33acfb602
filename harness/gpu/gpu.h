// The Vulkan backend, all of it: see README.md in this folder.
#pragma once

#include "buffer.h"        // Buffer, MemoryKind, BufferUsage, upload/download
#include "chunks.h"        // plan_chunks, groups_for
#include "commands.h"      // Commands, Recording, Stage, Groups
#include "context.h"       // Context, shared_context
#include "device_info.h"   // probe, DeviceInfo, DeviceLimits
#include "errors.h"        // Unavailable, Unsupported, VulkanError
#include "image.h"         // Image, write_png
#include "mesh_renderer.h" // MeshRenderer, Camera, render_image
#include "pipeline.h"      // ComputePipeline, GraphicsPipeline, DescriptorSet
#include "render_target.h" // RenderTarget
#include "spirv.h"         // Spirv
#include "timer.h"         // GpuTimer, PassKind
