// shiue2003-fig23: the paper's Figure 23, Conway's game of life as repeated adjustment without
// refinement on a Catmull-Clark-subdivided mesh, and its period-3 pulsar shown as three frames.
// Ours: pulsars placed in D-facets of a 4 x 4 torus refined five times (life.h), checked to
// repeat every third generation for 99 generations and never sooner, drawn on mipgh-cc's limit
// surface of the same mesh and depth (node for node the same nodes) into three PNGs.
#include <filesystem>
#include <sstream>

#include "datasets/manifest.h"
#include "harness/bench/paper_output.h"
#include "harness/core/paper_table.h"
#include "harness/core/registry.h"
#include "harness/gpu/context.h"
#include "harness/gpu/image.h"
#include "harness/gpu/mesh_renderer.h"
#include "schemes/mipgh/life.h"
#include "schemes/mipgh/mipgh.h"

namespace sdb::mipgh {
namespace {

constexpr const char* kMesh = "torus-4x4";
constexpr int kDepth = 5;
constexpr int kGenerations = 99;

bool same(const std::vector<V3>& a, const std::vector<V3>& b) {
  for (size_t i = 0; i < a.size(); ++i)
    if ((a[i].x > 0.5f) != (b[i].x > 0.5f)) return false;
  return true;
}

long alive(const std::vector<V3>& s) {
  long n = 0;
  for (const V3& v : s) n += v.x > 0.5f;
  return n;
}

// The three frames, or why there are none.
std::string draw(const ControlMesh& mesh, const std::vector<std::vector<V3>>& frames, const PaperTableOptions& options,
                 std::vector<std::string>& files) {
  std::shared_ptr<gpu::Context> ctx;
  try {
    ctx = gpu::shared_context();
  } catch (const std::exception& e) {
    return std::string("frames not drawn: ") + e.what();
  }
  const SchemeInfo& info = find_scheme("mipgh-cc")->info();
  auto e = make_evaluation(mesh, SubdivisionRule::CatmullClark, default_request(info, Backend::Cpu, kDepth));
  e->execute();
  const Tessellation& surface = e->result();
  std::filesystem::create_directories(options.out_dir);
  for (size_t g = 0; g < frames.size(); ++g) {
    std::vector<Point3> colours(surface.positions.size());
    for (size_t i = 0; i < colours.size(); ++i)
      colours[i] = frames[g][i].x > 0.5f ? Point3{0.60f, 0.08f, 0.08f} : Point3{0.90f, 0.88f, 0.82f};
    gpu::PictureOptions picture;
    picture.width = 640, picture.height = 480;
    const std::string file = "shiue2003-fig23-generation" + std::to_string(g) + ".png";
    gpu::write_png(gpu::render_image(*ctx, surface, colours, picture), (std::filesystem::path(options.out_dir) / file).string());
    files.push_back(file);
  }
  return "";
}

int run_fig23(const PaperTableOptions& options, std::ostream& out) {
  const ControlMesh mesh = load_mesh(kMesh);
  LifeOnMesh life(mesh, kDepth);
  const int margin = (life.facet_side() - 13) / 2;
  for (int f = 0; f < life.num_facets(); f += 3) life.place(f, margin, margin, pulsar());
  std::vector<std::vector<V3>> frames;
  for (int g = 0; g < 3; ++g, life.step()) frames.push_back(life.state());
  int repeats = 0;
  for (int g = 3; g < kGenerations; ++g, life.step()) repeats += same(life.state(), frames[g % 3]);
  const bool period3 = !same(frames[0], frames[1]) && !same(frames[0], frames[2]) && repeats == kGenerations - 3;
  std::vector<std::string> files;
  const std::string why = draw(mesh, frames, options, files);
  std::ostringstream md;
  md << "# shiue2003-fig23: the game of life on a subdivided mesh\n\n"
     << "The paper's Figure 23: \"a game of life simulation on a CC-subdivided mesh ... a period-3 'pulsar'\", "
        "repeated adjustment without refinement. Ours: mipgh's mesh processor visiting every node of `"
     << kMesh << "` refined " << kDepth << " times (" << life.state().size()
     << " nodes), the life rule B3/S23 as the mesh shader over each node's 1-disk; a pulsar placed in every third "
        "D-facet.\n\n| generation | alive nodes | frame |\n|---|---|---|\n";
  for (size_t g = 0; g < frames.size(); ++g)
    md << "| " << g << " | " << alive(frames[g]) << " | " << (g < files.size() ? files[g] : "-") << " |\n";
  md << "\nPeriod 3: " << (period3 ? "yes" : "NO") << " (generations 3.." << kGenerations - 1
     << " equal generation g mod 3 at every node: " << repeats << " of " << kGenerations - 3
     << "; generations 1 and 2 differ from 0).\n";
  if (!why.empty()) md << "\n" << why << "\n";
  publish(options, "shiue2003-fig23", md.str(), out);
  return period3 ? 0 : 1;
}

}  // namespace

std::vector<PaperTable> mipgh_figure_tables() {
  return {{"shiue2003-fig23", "Mesh mutation (MiPGH), Figure 23: the game of life on a subdivided mesh, a period-3 pulsar",
           run_fig23}};
}

}  // namespace sdb::mipgh
