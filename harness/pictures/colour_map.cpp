#include "harness/pictures/colour_map.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace sdb::pictures {
namespace {

// matplotlib's viridis at 17 evenly spaced points; linear in between.
constexpr std::array<Point3, 17> kViridis{{
    {0.267f, 0.005f, 0.329f}, {0.282f, 0.095f, 0.417f}, {0.279f, 0.175f, 0.483f}, {0.259f, 0.252f, 0.525f},
    {0.230f, 0.322f, 0.546f}, {0.199f, 0.388f, 0.555f}, {0.173f, 0.449f, 0.558f}, {0.149f, 0.508f, 0.557f},
    {0.128f, 0.567f, 0.551f}, {0.121f, 0.626f, 0.533f}, {0.158f, 0.684f, 0.502f}, {0.246f, 0.739f, 0.452f},
    {0.369f, 0.789f, 0.383f}, {0.516f, 0.831f, 0.294f}, {0.678f, 0.864f, 0.190f}, {0.846f, 0.887f, 0.100f},
    {0.993f, 0.906f, 0.144f},
}};

uint8_t to_byte(float v) { return static_cast<uint8_t>(std::lround(255.0f * std::clamp(v, 0.0f, 1.0f))); }

}  // namespace

Point3 viridis(float t) {
  if (!(t > 0.0f)) return kViridis.front();
  if (t >= 1.0f) return kViridis.back();
  const float x = t * float(kViridis.size() - 1);
  const size_t i = static_cast<size_t>(x);
  const float f = x - float(i);
  const Point3 &a = kViridis[i], &b = kViridis[i + 1];
  return {a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1]), a[2] + f * (b[2] - a[2])};
}

gpu::Image colour_bar(uint32_t width, uint32_t height) {
  gpu::Image bar;
  bar.width = width;
  bar.height = height;
  bar.rgba.resize(size_t(width) * height * 4);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      const bool frame = x == 0 || y == 0 || x + 1 == width || y + 1 == height;
      const Point3 c = frame ? Point3{0.45f, 0.45f, 0.45f} : viridis(float(x - 1) / float(std::max(width, 3u) - 3));
      uint8_t* p = &bar.rgba[(size_t(y) * width + x) * 4];
      p[0] = to_byte(c[0]), p[1] = to_byte(c[1]), p[2] = to_byte(c[2]), p[3] = 255;
    }
  return bar;
}

}  // namespace sdb::pictures
