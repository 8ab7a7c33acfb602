// shiue2003-fig22: the paper's Figure 22, different mesh shaders applied to the same input:
// Catmull-Clark, quad/triangle, Catmull-Clark with creases, and normal displacement from a
// texture (read with OpenImageIO; refinement bypassed). Ours: Spot's control mesh (quads,
// triangles after the R1 split, pentagons), each shader's surface drawn offscreen into a PNG, and
// each checked watertight (0 open edges, no ray crack).
#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>

#include "datasets/manifest.h"
#include "harness/bench/paper_output.h"
#include "harness/core/errors.h"
#include "harness/core/paper_table.h"
#include "harness/core/registry.h"
#include "harness/gpu/context.h"
#include "harness/gpu/image.h"
#include "harness/gpu/mesh_renderer.h"
#include "harness/mesh/acceptance.h"
#include "harness/validate/watertight.h"
#include "schemes/mipgh/atlas.h"
#include "schemes/mipgh/displacement.h"
#include "schemes/mipgh/lod.h"
#include "schemes/mipgh/mipgh.h"

namespace sdb::mipgh {
namespace {

constexpr float kCreaseAngle = 40.0f;  // degrees between two faces' normals: a feature edge
constexpr float kCreaseSharpness = 4.0f;

struct Panel {
  std::string shader, file, note;
  Tessellation surface;
  long open = -1, cracks = -1, rays = 0;
};

Point3 face_normal(const ControlMesh& m, const int* v, int n) {  // Newell's
  double x = 0, y = 0, z = 0;
  for (int i = 0; i < n; ++i) {
    const Point3 &a = m.positions[v[i]], &b = m.positions[v[(i + 1) % n]];
    x += (double(a[1]) - b[1]) * (double(a[2]) + b[2]);
    y += (double(a[2]) - b[2]) * (double(a[0]) + b[0]);
    z += (double(a[0]) - b[0]) * (double(a[1]) + b[1]);
  }
  const double l = std::sqrt(x * x + y * y + z * z);
  return l > 0 ? Point3{float(x / l), float(y / l), float(z / l)} : Point3{0, 0, 0};
}

// The input with its feature edges (faces meeting at more than kCreaseAngle) creased.
ControlMesh with_feature_creases(ControlMesh m) {
  const std::vector<int> off = face_offsets(m);
  std::map<std::pair<int, int>, std::vector<Point3>> edges;
  for (int f = 0; f < num_faces(m); ++f) {
    const int n = m.face_sizes[f], *v = m.face_vertices.data() + off[f];
    const Point3 normal = face_normal(m, v, n);
    for (int i = 0; i < n; ++i) edges[std::minmax(v[i], v[(i + 1) % n])].push_back(normal);
  }
  for (const auto& [e, normals] : edges) {
    if (normals.size() != 2) continue;
    const double dot = double(normals[0][0]) * normals[1][0] + double(normals[0][1]) * normals[1][1] +
                       double(normals[0][2]) * normals[1][2];
    if (dot < std::cos(kCreaseAngle * M_PI / 180)) m.creases.push_back({e.first, e.second, kCreaseSharpness});
  }
  return m;
}

// Area-weighted vertex normals, for drawing a surface that has none (the quad/triangle nodes).
void polyhedron_normals(Tessellation& t) {
  t.normals.assign(t.positions.size(), Point3{0, 0, 0});
  for (size_t k = 0; k + 2 < t.triangles.size(); k += 3) {
    const Point3 &a = t.positions[t.triangles[k]], &b = t.positions[t.triangles[k + 1]], &c = t.positions[t.triangles[k + 2]];
    const float u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const float n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) t.normals[t.triangles[k + i]][j] += n[j];
  }
  for (Point3& n : t.normals) {
    const float l = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (l > 0) n = {n[0] / l, n[1] / l, n[2] / l};
  }
}

Tessellation evaluate(const ControlMesh& input, MeshRule rule, int depth, ControlMesh& accepted) {
  const char* name = rule == MeshRule::QuadTri ? "mipgh-quadtri" : "mipgh-cc";
  const SchemeInfo& info = find_scheme(name)->info();
  accepted = accept_mesh(input, info);
  auto e = make_evaluation(accepted, rule, default_request(info, Backend::Cpu, depth), rule != MeshRule::QuadTri);
  e->execute();
  return e->result();
}

// The displacement map: the user's (--texture), or bumps written to a PNG and read back, so
// that both take OpenImageIO's path.
DisplacementMap displacement_map(const PaperTableOptions& options, std::string& source) {
  if (!options.texture.empty()) {
    source = options.texture;
    return read_displacement(options.texture);
  }
  const DisplacementMap made = bumps(256);
  gpu::Image image{uint32_t(made.width), uint32_t(made.height), {}};
  for (float v : made.values) {
    const uint8_t g = uint8_t(std::lround(v * 255));
    image.rgba.insert(image.rgba.end(), {g, g, g, 255});
  }
  std::filesystem::create_directories(options.out_dir);
  source = (std::filesystem::path(options.out_dir) / "shiue2003-fig22-displacement.png").string();
  gpu::write_png(image, source);
  return read_displacement(source);
}

int run_fig22(const PaperTableOptions& options, std::ostream& out) {
  const int depth = options.quick ? 2 : 3;
  ControlMesh input;
  std::string input_note;
  try {
    input = load_mesh("crane/spot_control");
  } catch (const InputError& e) {
    input = load_mesh("quadsphere");
    input_note = std::string("(Spot's control mesh is not here: ") + e.what() + "; the quad sphere instead)";
  }
  std::string texture;
  const DisplacementMap map = displacement_map(options, texture);  // refused before any work
  std::vector<Panel> panels(4);
  ControlMesh cc_mesh, qt_mesh, crease_mesh;
  panels[0] = {"Catmull-Clark (limit)", "", "", evaluate(input, MeshRule::CatmullClark, depth, cc_mesh)};
  panels[1] = {"quad/triangle (Stam and Loop, last level)", "", "", evaluate(input, MeshRule::QuadTri, depth, qt_mesh)};
  polyhedron_normals(panels[1].surface);
  const ControlMesh creased = with_feature_creases(input);
  panels[2] = {"Catmull-Clark with creases (limit)", "", "", evaluate(creased, MeshRule::CatmullClark, depth, crease_mesh)};
  panels[2].note = std::to_string(creased.creases.size()) + " feature edges (over " + std::to_string(int(kCreaseAngle)) +
                   " degrees) creased, sharpness " + std::to_string(int(kCreaseSharpness));
  panels[3] = {"Catmull-Clark, normal displacement (refinement bypassed)", "", "", panels[0].surface};
  const float scale = 0.02f * float(bounds_of(cc_mesh.positions).diagonal());
  const DAtlas atlas = build_atlas(cc_mesh);
  displace_along_normals(atlas, DLoD(atlas, depth), depth, ChartAttribute::unit_charts(atlas, depth), map, scale,
                         panels[3].surface);
  panels[3].note = "2% of the diagonal times the image; drawn with the displaced polyhedron's normals";
  bool watertight = true;
  // the limit normals moved with the surface no longer fit it: the picture shades the polyhedron's
  polyhedron_normals(panels[3].surface);
  for (Panel& p : panels) {
    p.open = count_open_edges(p.surface);
    const RayCrackReport r = ray_crack_check(p.surface, {10000, 10000, 5});
    p.cracks = r.cracks, p.rays = r.rays;
    watertight = watertight && p.open == 0 && p.cracks == 0;
  }
  std::string why;
  try {
    auto ctx = gpu::shared_context();
    std::filesystem::create_directories(options.out_dir);
    const Point3 colours[4] = {{0.80f, 0.78f, 0.70f}, {0.62f, 0.74f, 0.86f}, {0.86f, 0.70f, 0.55f}, {0.70f, 0.82f, 0.66f}};
    for (size_t k = 0; k < panels.size(); ++k) {
      gpu::PictureOptions picture;
      picture.width = 640, picture.height = 480;
      panels[k].file = "shiue2003-fig22-" + std::to_string(k + 1) + ".png";
      const std::vector<Point3> colour(panels[k].surface.positions.size(), colours[k]);
      gpu::write_png(gpu::render_image(*ctx, panels[k].surface, colour, picture),
                     (std::filesystem::path(options.out_dir) / panels[k].file).string());
    }
  } catch (const std::exception& e) {
    why = std::string("pictures not drawn: ") + e.what();
  }
  std::ostringstream md;
  md << "# shiue2003-fig22: different mesh shaders on the same input\n\n"
     << "The paper's Figure 22: Catmull-Clark, quad/triangle subdivision, Catmull-Clark with creases and normal "
        "displacement applied by the same mesh processor to one input. Ours: `"
     << input.name << "` " << (input_note.empty() ? "" : input_note + " ") << "(" << num_faces(input) << " faces) at depth " << depth
     << "; Catmull-Clark takes it quadrangulated by one step, quad/triangle with its larger faces split (R1); the "
        "displacement reads `"
     << texture << "` (" << map.width << " x " << map.height << ", OpenImageIO) at each node's place in its D-facet.\n\n"
     << "| shader | triangles | open edges | ray cracks | picture | note |\n|---|---|---|---|---|---|\n";
  for (const Panel& p : panels)
    md << "| " << p.shader << " | " << p.surface.triangles.size() / 3 << " | " << p.open << " | " << p.cracks << " of "
       << p.rays << " | " << (p.file.empty() ? "-" : p.file) << " | " << p.note << " |\n";
  md << "\nWatertight: " << (watertight ? "yes" : "NO") << " (every surface closed, no ray crack).\n";
  if (!why.empty()) md << "\n" << why << "\n";
  publish(options, "shiue2003-fig22", md.str(), out);
  return watertight ? 0 : 1;
}

}  // namespace

std::vector<PaperTable> mipgh_fig22_tables() {
  return {{"shiue2003-fig22",
           "Mesh mutation (MiPGH), Figure 22: Catmull-Clark, quad/triangle, creases and normal displacement on one input",
           run_fig22}};
}

}  // namespace sdb::mipgh
