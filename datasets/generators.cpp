#include "datasets/generators.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <tuple>

#include "harness/core/errors.h"

namespace sdb::gen {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

ControlMesh named(std::string name, std::vector<Point3> pos, std::vector<int> sizes, std::vector<int> fv) {
  ControlMesh m;
  m.source = "builtin:" + name;
  m.name = std::move(name);
  m.positions = std::move(pos);
  m.face_sizes = std::move(sizes);
  m.face_vertices = std::move(fv);
  return m;
}

void add_quad(ControlMesh& m, int a, int b, int c, int d) {
  m.face_sizes.push_back(4);
  m.face_vertices.insert(m.face_vertices.end(), {a, b, c, d});
}

}  // namespace

ControlMesh cube() {
  ControlMesh m = named("cube",
                        {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}, {-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}},
                        {}, {});
  add_quad(m, 0, 3, 2, 1);  // z = -1, normal -z
  add_quad(m, 4, 5, 6, 7);  // z = +1
  add_quad(m, 0, 1, 5, 4);  // y = -1
  add_quad(m, 2, 3, 7, 6);  // y = +1
  add_quad(m, 1, 2, 6, 5);  // x = +1
  add_quad(m, 3, 0, 4, 7);  // x = -1
  return m;
}

ControlMesh torus(int m, int n, float major, float minor) {
  if (m < 3 || n < 3) throw InputError("torus", "needs at least 3 x 3 quads");
  ControlMesh t = named("torus-" + std::to_string(m) + "x" + std::to_string(n), {}, {}, {});
  // i runs around the tube (m), j around the main circle (n).
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < m; ++i) {
      const float a = 2 * kPi * j / n, b = 2 * kPi * i / m;
      const float r = major + minor * std::cos(b);
      t.positions.push_back({r * std::cos(a), r * std::sin(a), minor * std::sin(b)});
    }
  auto id = [&](int i, int j) { return ((j + n) % n) * m + (i + m) % m; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < m; ++i) add_quad(t, id(i, j), id(i, j + 1), id(i + 1, j + 1), id(i + 1, j));
  return t;
}

ControlMesh quad_sphere(int k) {
  if (k < 1) throw InputError("quadsphere", "needs k >= 1");
  ControlMesh s = named("quadsphere-" + std::to_string(k), {}, {}, {});
  std::map<std::tuple<int, int, int>, int> index;  // lattice point on the cube surface -> vertex
  auto vertex = [&](int x, int y, int z) {
    auto [it, added] = index.try_emplace({x, y, z}, num_vertices(s));
    if (added) {
      float p[3] = {2.0f * x / k - 1, 2.0f * y / k - 1, 2.0f * z / k - 1};
      const float len = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
      s.positions.push_back({p[0] / len, p[1] / len, p[2] / len});
    }
    return it->second;
  };
  // Each cube face: axis `a` fixed at 0 or k; (u, v) span the other two so that u x v points out.
  for (int a = 0; a < 3; ++a)
    for (int side = 0; side < 2; ++side) {
      const int ua = (a + 1) % 3, va = (a + 2) % 3;
      for (int i = 0; i < k; ++i)
        for (int j = 0; j < k; ++j) {
          int c[4][2] = {{i, j}, {i + 1, j}, {i + 1, j + 1}, {i, j + 1}};
          int ids[4];
          for (int q = 0; q < 4; ++q) {
            int p[3];
            p[a] = side * k;
            p[ua] = c[q][0];
            p[va] = c[q][1];
            ids[q] = vertex(p[0], p[1], p[2]);
          }
          if (side == 1) add_quad(s, ids[0], ids[1], ids[2], ids[3]);
          else add_quad(s, ids[0], ids[3], ids[2], ids[1]);
        }
    }
  return s;
}

ControlMesh pole(int n, int bands) {
  if (n < 3) throw InputError("pole", "valence must be at least 3");
  // Two caps of n quads around a valence-n centre, joined by `bands` rings of 2n quads; laid on a
  // sphere. Caps share a 2n-vertex ring with the bands.
  ControlMesh m = named("pole" + std::to_string(n), {}, {}, {});
  const int ring = 2 * n, rings = bands + 1;
  m.positions.push_back({0, 0, 1});  // top pole
  for (int r = 0; r < rings; ++r) {
    const float theta = kPi * (r + 1) / (rings + 1);
    for (int j = 0; j < ring; ++j) {
      const float phi = 2 * kPi * j / ring;
      m.positions.push_back({std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)});
    }
  }
  m.positions.push_back({0, 0, -1});  // bottom pole
  const int top = 0, bottom = num_vertices(m) - 1;
  auto at = [&](int r, int j) { return 1 + r * ring + (j % ring); };
  for (int i = 0; i < n; ++i) add_quad(m, top, at(0, 2 * i), at(0, 2 * i + 1), at(0, 2 * i + 2));
  for (int r = 0; r + 1 < rings; ++r)
    for (int j = 0; j < ring; ++j) add_quad(m, at(r, j), at(r + 1, j), at(r + 1, j + 1), at(r, j + 1));
  for (int i = 0; i < n; ++i)
    add_quad(m, bottom, at(rings - 1, 2 * i + 2), at(rings - 1, 2 * i + 1), at(rings - 1, 2 * i));
  return m;
}

ControlMesh icosphere(int level) {
  const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
  std::vector<Point3> p = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                           {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  std::vector<int> tri = {0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4, 11, 10, 2, 10, 7, 6,
                          7, 1, 8, 3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8, 3, 8, 9, 4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7, 9, 8, 1};
  auto normalize = [](Point3 a) {
    const float l = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    return Point3{a[0] / l, a[1] / l, a[2] / l};
  };
  for (auto& q : p) q = normalize(q);
  for (int l = 0; l < level; ++l) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      auto [it, added] = mid.try_emplace({std::min(a, b), std::max(a, b)}, static_cast<int>(p.size()));
      if (added) p.push_back(normalize({p[a][0] + p[b][0], p[a][1] + p[b][1], p[a][2] + p[b][2]}));
      return it->second;
    };
    std::vector<int> next;
    for (size_t f = 0; f < tri.size(); f += 3) {
      const int a = tri[f], b = tri[f + 1], c = tri[f + 2];
      const int ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      next.insert(next.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    tri = std::move(next);
  }
  std::vector<int> sizes(tri.size() / 3, 3);
  return named("icosphere-" + std::to_string(level), std::move(p), std::move(sizes), std::move(tri));
}

ControlMesh tetrahedron() {
  return named("tetrahedron", {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}}, {3, 3, 3, 3},
               {0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2});
}

ControlMesh creased_cube(float sharpness) {
  ControlMesh m = cube();
  m.name = "creased-cube";
  m.source = "builtin:creased-cube";
  const int edges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6}, {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  for (const auto& e : edges) m.creases.push_back({e[0], e[1], sharpness});
  return m;
}

ControlMesh open_patch(int m, int n) {
  ControlMesh p = named("open-patch-" + std::to_string(m) + "x" + std::to_string(n), {}, {}, {});
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= m; ++i) {
      const float x = float(i) / m, y = float(j) / n;
      p.positions.push_back({x, y, 0.15f * std::sin(2 * kPi * x) * std::cos(kPi * y)});
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < m; ++i) {
      const int a = j * (m + 1) + i;
      add_quad(p, a, a + 1, a + m + 2, a + m + 1);
    }
  return p;
}

ControlMesh split_quads(const ControlMesh& mesh) {
  ControlMesh out = mesh;
  out.name = mesh.name + "-triangles";
  out.face_sizes.clear(), out.face_vertices.clear(), out.face_lines.clear();
  const std::vector<int> off = face_offsets(mesh);
  for (int f = 0; f < num_faces(mesh); ++f) {
    const int* v = mesh.face_vertices.data() + off[f];
    if (mesh.face_sizes[f] != 4) {
      out.face_sizes.push_back(mesh.face_sizes[f]);
      out.face_vertices.insert(out.face_vertices.end(), v, v + mesh.face_sizes[f]);
      continue;
    }
    const int k = f % 3 == 0 ? 1 : 0;  // the diagonal's first corner
    out.face_sizes.insert(out.face_sizes.end(), {3, 3});
    out.face_vertices.insert(out.face_vertices.end(), {v[k], v[k + 1], v[k + 2], v[k], v[k + 2], v[(k + 3) % 4]});
  }
  out.holes.clear();
  return out;
}

ControlMesh party(const ControlMesh& mesh, int copies) {
  ControlMesh out = mesh;
  out.name = mesh.name + "-party" + std::to_string(copies);
  out.source = "builtin:" + out.name;
  out.face_lines.clear();
  float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
  for (const auto& p : mesh.positions)
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
  const float step = 1.2f * std::max({hi[0] - lo[0], hi[1] - lo[1], 1e-6f});
  const int cols = static_cast<int>(std::ceil(std::sqrt(double(copies))));
  const int nv = num_vertices(mesh);
  for (int c = 1; c < copies; ++c) {
    const float dx = step * (c % cols), dy = step * (c / cols);
    for (const auto& p : mesh.positions) out.positions.push_back({p[0] + dx, p[1] + dy, p[2]});
    out.face_sizes.insert(out.face_sizes.end(), mesh.face_sizes.begin(), mesh.face_sizes.end());
    for (int v : mesh.face_vertices) out.face_vertices.push_back(v + c * nv);
    for (auto cr : mesh.creases) out.creases.push_back({cr.v0 + c * nv, cr.v1 + c * nv, cr.sharpness});
    for (auto co : mesh.corners) out.corners.push_back({co.vertex + c * nv, co.sharpness});
    for (int h : mesh.holes) out.holes.push_back(h + c * num_faces(mesh));
  }
  return out;
}

}  // namespace sdb::gen
