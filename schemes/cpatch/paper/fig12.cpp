// ni2008-fig12: the c-patch surface against the Catmull-Clark limit on the same input, as the
// paper's Figure 12 measures it (distance in % of the local quad size, normal deviation in
// degrees), as a distribution per mesh, with a heat map of the position deviation rendered by
// cpatch-2pass's own render path (grid_heat.vert colours each output vertex).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "harness/core/errors.h"
#include "harness/core/registry.h"
#include "harness/gpu/errors.h"
#include "harness/gpu/gpu.h"
#include "harness/results/markdown.h"
#include "harness/validate/deviation.h"
#include "schemes/cpatch/cpu.h"
#include "schemes/cpatch/paper/paper.h"
#include "schemes/cpatch/vulkan.h"

namespace sdb::cpatch {
namespace {

struct Fig12Mesh {
  std::string label, mesh;
};

const Fig12Mesh kMeshes[] = {{"Spot", "crane/spot_control"},          {"Blub", "crane/blub_control"},
                             {"Fandisk", "pmp/fandisk_quads"},         {"Sword (22k quads)", "stein/sword_quad_dominant"},
                             {"Sword stand-in", "sword-standin"},      {"Head stand-in", "head-standin"},
                             {"Frog stand-in", "frog-standin"}};

// shading.glsl heat_colour(): blue (0) - white (1/2) - red (1).
std::array<uint8_t, 4> heat_colour(float t) {
  t = std::clamp(t, 0.0f, 1.0f);
  const float blue[3] = {0.23f, 0.30f, 0.75f}, white[3] = {0.87f, 0.87f, 0.87f}, red[3] = {0.71f, 0.02f, 0.15f};
  std::array<uint8_t, 4> c{0, 0, 0, 255};
  for (int k = 0; k < 3; ++k) {
    const float v = t < 0.5f ? blue[k] + (white[k] - blue[k]) * 2 * t : white[k] + (red[k] - white[k]) * (2 * t - 1);
    c[k] = static_cast<uint8_t>(std::lround(255 * v));
  }
  return c;
}

// The colour scale along the bottom left of the picture, 0 at the left, `scale` at the right.
void draw_colour_bar(gpu::Image& image) {
  const uint32_t x0 = 24, width = std::min<uint32_t>(320, image.width / 3), height = 14;
  const uint32_t y0 = image.height - 24 - height;
  for (uint32_t y = y0; y < y0 + height; ++y)
    for (uint32_t x = x0; x < x0 + width; ++x) {
      const auto c = heat_colour(float(x - x0) / float(width - 1));
      std::copy(c.begin(), c.end(), &image.rgba[(size_t(y) * image.width + x) * 4]);
    }
}

double percentile(std::vector<float> values, double p) {
  if (values.empty()) return 0;
  const size_t k = std::min(values.size() - 1, static_cast<size_t>(p * (values.size() - 1)));
  std::nth_element(values.begin(), values.begin() + static_cast<long>(k), values.end());
  return values[k];
}

std::string file_stem(const std::string& mesh) {
  std::string s = mesh;
  std::replace(s.begin(), s.end(), '/', '_');
  return "ni2008-fig12-" + s;
}

struct Fig12Result {
  std::string label, mesh, shape, source, picture, failure;
  int quads = 0, cpatches = 0;
  DeviationReport deviation;
  double heat_scale = 0;
};

// The c-patch output at rate N: from the Vulkan evaluate-only path when there is a device (its
// positions are the CPU's bit for bit, see cpatch_vulkan_test), else from cpu-mt.
Tessellation cpatch_output(const ControlMesh& quads, int rate, std::string& source, int& cpatches) {
  if (!vulkan_unsupported(GpuVariant::TwoPass, GpuMode::Evaluate, rate)) {
    CpatchVulkanEvaluation eval(quads, rate, GpuVariant::TwoPass);
    eval.execute();
    cpatches = static_cast<int>(eval.engine().topology().extraordinary_quads.size());
    source = "cpatch-2pass/vulkan";
    return eval.result();
  }
  CpatchCpuEvaluation eval(quads, rate, true);
  eval.execute();
  cpatches = static_cast<int>(eval.topology().extraordinary_quads.size());
  source = "cpatch-2pass/cpu-mt";
  return eval.output();
}

// Renders the c-patch surface coloured by each output vertex's position deviation and writes it.
std::string write_heat_map(const ControlMesh& quads, int rate, const DeviationReport& d, double scale,
                           const PaperTableOptions& o, const std::string& mesh) {
  GpuOptions options;
  options.mode = GpuMode::Render;
  options.heat_values = d.vertex_pct;
  options.heat_scale = static_cast<float>(scale);
  CpatchVulkan renderer(quads, rate, options);
  renderer.execute();
  gpu::Image image = renderer.read_image();
  draw_colour_bar(image);
  const std::string name = file_stem(mesh) + ".png";
  gpu::write_png(image, (std::filesystem::path(o.out_dir) / name).string());
  return name;
}

Fig12Result measure_mesh(const Fig12Mesh& m, int rate, const PaperTableOptions& o, MeasureContext& context) {
  Fig12Result r;
  r.label = m.label;
  r.mesh = m.mesh;
  std::shared_ptr<const ControlMesh> quads;
  try {
    quads = context.accepted(m.mesh, *find_scheme("cpatch-2pass"));
  } catch (const InputError& e) {
    r.failure = e.what();
    return r;
  }
  std::fprintf(stderr, "ni2008-fig12: %s N=%d\n", m.mesh.c_str(), rate);
  r.shape = mesh_shape(context, m.mesh, *quads);
  r.quads = num_faces(*quads);
  const Tessellation out = cpatch_output(*quads, rate, r.source, r.cpatches);
  r.deviation = measure_deviation(out, context.reference(quads, SubdivisionRule::CatmullClark));
  // Red from the 99th percentile up: the largest deviations sit at a few samples near
  // high-valence vertices and would wash the rest of the picture out.
  r.heat_scale = std::max(percentile(r.deviation.vertex_pct, 0.99), 1e-6);
  if (!vulkan_unsupported(GpuVariant::TwoPass, GpuMode::Render, rate)) {
    try {
      r.picture = write_heat_map(*quads, rate, r.deviation, r.heat_scale, o, m.mesh);
    } catch (const gpu::Unsupported& e) {
      r.picture = std::string("(no picture: ") + e.what() + ")";
    }
  } else {
    r.picture = "(no picture: no Vulkan device)";
  }
  return r;
}

void write_table(std::ostringstream& md, const std::vector<Fig12Result>& rows, int rate) {
  MarkdownTable table({"mesh (verts, quads, eqs)", "quads, c-patches", "N", "position max %", "mean %", "RMS %", "p95 %",
                       "normal max °", "mean °", "RMS °", "p95 °", "heat map: red at (p99)"});
  for (const Fig12Result& r : rows) {
    if (!r.failure.empty()) {
      table.add_row({r.label + " (" + r.mesh + ")", r.failure});
      continue;
    }
    const DeviationReport& d = r.deviation;
    table.add_row({r.label + " (" + r.mesh + ") " + r.shape, std::to_string(r.quads) + ", " + std::to_string(r.cpatches),
                   std::to_string(rate), fixed(d.pos_max_pct, 2), fixed(d.pos_mean_pct, 3), fixed(d.pos_rms_pct, 3),
                   fixed(d.pos_p95_pct, 4), fixed(d.normal_max_deg, 2), fixed(d.normal_mean_deg, 3),
                   fixed(d.normal_rms_deg, 3), fixed(d.normal_p95_deg, 4), fixed(r.heat_scale, 3) + " %"});
  }
  table.write(md);
}

}  // namespace

int run_fig12(const PaperTableOptions& o, std::ostream& out) {
  MeasureContext context(describe_machine());
  const int rate = o.quick ? 5 : 9;
  std::vector<Fig12Mesh> meshes(std::begin(kMeshes), std::end(kMeshes));
  if (o.quick) meshes = {{"Sword stand-in", "sword-standin"}};
  std::filesystem::create_directories(o.out_dir);
  std::vector<Fig12Result> rows;
  for (const Fig12Mesh& m : meshes) rows.push_back(measure_mesh(m, rate, o, context));

  std::ostringstream md;
  md << "# ni2008-fig12 — GPU Smoothing of Quad Meshes, Figure 12: c-patch surface against the Catmull-Clark limit\n\n";
  md << "The paper shows colour plots (geometric distance in % of the local quad size, normal deviation in degrees) "
        "without figures; here the same two measures as distributions over every output vertex at N = "
     << rate
     << ": the distance to the Catmull-Clark limit point (OpenSubdiv) at the same (face, u, v), in % of the quad's "
        "mean edge length (after the Catmull-Clark step that makes quads), and the angle between the normals.\n\n";
  md << "Output: " << (rows.empty() ? "" : rows.front().source) << "; device: " << device_line() << ".\n\n";
  write_table(md, rows, rate);
  md << "\nHeat maps: the c-patch tessellation rendered by cpatch-2pass's render path (Vulkan), each output vertex "
        "coloured by its position deviation on a blue (0) - white - red scale, red from the 99th percentile of the "
        "mesh's deviations up (the bar at the bottom left runs from 0 to that value).\n\n";
  for (const Fig12Result& r : rows)
    if (!r.picture.empty() && r.picture.front() != '(') md << "![" << r.label << "](" << r.picture << ")\n";
  if (o.quick) md << "\n(--quick: the sword stand-in only, at N = 5.)\n";
  publish(o, "ni2008-fig12", md.str(), out);
  return 0;
}

}  // namespace sdb::cpatch
