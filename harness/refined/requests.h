// What the uniform-refinement peers (schemes/halfedge, schemes/edgefriend) ask of a request alike:
// a depth 1..8 (past 8 their 32-bit indices run out on any real mesh), on cpu, cpu-mt or vulkan.
#pragma once

#include <optional>
#include <string>

#include "harness/core/scheme.h"

namespace sdb::refined {

constexpr int kMaxDepth = 8;

// Why Vulkan cannot run here (no device), once per process; none where it can: their passes bind
// at most fourteen texel views, within Vulkan's minimum limits.
std::optional<std::string> vulkan_unavailable();

// Why `scheme` does not take the request; none where it does.
std::optional<std::string> unsupported_request(const RunRequest& r, const std::string& scheme);

}  // namespace sdb::refined
