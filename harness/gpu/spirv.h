// Spirv: one embedded SPIR-V module, as sdb_add_shaders (cmake/Shaders.cmake) generates them.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

namespace sdb::gpu {

struct Spirv {
  std::string_view name;  // the GLSL file name, e.g. "subdivide.comp"
  std::span<const uint32_t> words;
};

}  // namespace sdb::gpu
