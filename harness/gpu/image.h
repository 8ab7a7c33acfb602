// The host image a render target reads back into: harness/images' Image, under the name the
// Vulkan code and its callers use.
#pragma once

#include "harness/images/image.h"

namespace sdb::gpu {

using images::Image;
using images::read_image;
using images::write_png;

}  // namespace sdb::gpu
