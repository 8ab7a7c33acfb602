#include "schemes/mipgh/displacement.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "harness/core/errors.h"
#include "harness/gpu/image.h"

namespace sdb::mipgh {

float DisplacementMap::sample(float u, float v) const {
  const float x = std::clamp(u, 0.0f, 1.0f) * float(width - 1), y = std::clamp(v, 0.0f, 1.0f) * float(height - 1);
  const int x0 = std::min(int(x), width - 1), y0 = std::min(int(y), height - 1);
  const int x1 = std::min(x0 + 1, width - 1), y1 = std::min(y0 + 1, height - 1);
  const float fx = x - float(x0), fy = y - float(y0);
  auto at = [&](int i, int j) { return values[size_t(j) * width + i]; };
  return (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x1, y0)) + fy * ((1 - fx) * at(x0, y1) + fx * at(x1, y1));
}

DisplacementMap read_displacement(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path, "no such displacement image");
  gpu::Image image;
  try {
    image = gpu::read_image(path);
  } catch (const std::exception& e) {
    throw InputError(path, std::string("unreadable displacement image: ") + e.what());
  }
  if (image.width < 2 || image.height < 2) throw InputError(path, "a displacement image needs at least 2 x 2 pixels");
  DisplacementMap m{int(image.width), int(image.height), {}};
  m.values.resize(size_t(m.width) * m.height);
  for (size_t p = 0; p < m.values.size(); ++p) m.values[p] = float(image.rgba[p * 4]) / 255.0f;
  return m;
}

DisplacementMap bumps(int size) {
  DisplacementMap m{size, size, std::vector<float>(size_t(size) * size)};
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      const float u = float(i) / float(size - 1), v = float(j) / float(size - 1);
      m.values[size_t(j) * size + i] = std::sin(float(M_PI) * u) * std::sin(float(M_PI) * v);
    }
  return m;
}

void displace_along_normals(const DAtlas& atlas, const DLoD& lod, int depth, const ChartAttribute& coords,
                            const DisplacementMap& map, float scale, Tessellation& t) {
  const int n = lod.layout(depth).n;
  std::vector<char> done(t.positions.size(), 0);
  for (int f = 0; f < atlas.num_facets(); ++f) {
    const uint32_t* idx = lod.facet(depth, f);
    const bool quad = atlas.facet_size[f] == 4;
    for (int i = 0; i < n; ++i)
      for (int j = 0; quad ? j < n : i + j < n; ++j) {
        const uint32_t node = idx[facet_offset(quad ? 4 : 3, n, {i, j})];
        if (done[node]) continue;
        done[node] = 1;
        const ChartValue& uv = coords.at(depth, f, {i, j});
        const float h = scale * map.sample(uv[0], uv[1]);
        Point3& p = t.positions[node];
        const Point3& q = t.normals[node];
        for (int k = 0; k < 3; ++k) p[k] += h * q[k];
      }
  }
}

}  // namespace sdb::mipgh
