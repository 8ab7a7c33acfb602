// A 64-bit FNV-1a hash of bytes: what says that a file (a run's input mesh, a cached geometry
// image's pixels) is the one that was recorded. Not a defence against an adversary who forges
// collisions; a check that the bytes did not change, by an edit, a truncation or a flipped bit.
#pragma once

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <optional>
#include <string>
#include <string_view>

namespace sdb {

inline constexpr uint64_t kFnvOffset = 14695981039346656037ull;

inline uint64_t fnv1a_64(std::string_view bytes, uint64_t h = kFnvOffset) {
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

// The hash of a file's bytes, or nullopt when it cannot be read.
inline std::optional<uint64_t> file_content_hash(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  uint64_t h = kFnvOffset;
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) h = fnv1a_64({buffer, size_t(in.gcount())}, h);
  if (in.bad()) return std::nullopt;
  return h;
}

inline std::string hex64(uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

}  // namespace sdb
