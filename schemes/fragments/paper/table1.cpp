// shiue-loop-table1 (TABLES.md): frames per second of Loop subdivision with mesh fragments at
// depth 4 and 5, refine + limit + render into a 1024 x 768 offscreen target, from timestamps,
// beside the poster's four configurations; the same cells for fragments-cc on quad meshes, and
// the CPU peer (osd-uniform-loop, osd-uniform, one thread) measured in the same run.
#include <chrono>
#include <sstream>

#include "harness/bench/machine.h"
#include "harness/bench/measure.h"
#include "harness/bench/paper_output.h"
#include "harness/core/errors.h"
#include "harness/core/registry.h"
#include "harness/gpu/errors.h"
#include "harness/mesh/facts.h"
#include "harness/results/markdown.h"
#include "harness/results/statistics.h"
#include "schemes/fragments/vulkan.h"

namespace sdb::fragments {
namespace {

// The poster's models are not public. Stand-ins: closed corpus triangle meshes of a few hundred
// to a few thousand faces, in the poster's order of size (venus, the slowest, is the largest).
struct Model {
  const char* paper;  // the poster's model; nullptr for quad meshes the poster did not show
  const char* mesh;
  const char* why;
};
const Model kLoopModels[] = {
    {"liver", "pmp/icosahedron_subdiv", "a smooth closed organ-like blob of 1,280 triangles"},
    {"stomach", "crane/spot_low_resolution", "an organic closed surface of 1,654 triangles"},
    {"mechpart", "stein/torus", "genus 1, like a machined ring, 4,608 triangles"},
    {"venus", "stanford/bunny", "the largest, a scanned statue-like model of 6,598 triangles"},
};
const Model kQuadModels[] = {
    {nullptr, "crane/blub_control", ""},
    {nullptr, "crane/spot_control", ""},
    {nullptr, "pmp/fandisk_quads", ""},
};
// The poster's fps: config 1 Radeon 9700 Pro, 2 GeForce 6800GT (PBO/VBO), 3 GeForce 6200,
// 4 Radeon X800; per model, depth 4 then 5.
const double kPaperFps[4][8] = {{9.70, 6.27, 8.53, 4.41, 7.62, 4.60, 4.27, 1.88},
                                {22.83, 15.63, 19.42, 11.43, 18.28, 13.07, 9.70, 5.24},
                                {18.32, 9.15, 12.08, 4.85, 13.62, 6.81, 5.04, 1.90},
                                {13.91, 8.42, 11.43, 5.71, 10.33, 6.04, 5.42, 2.40}};
const int kDepths[] = {4, 5};

struct Cell {
  int depth = 0;
  long triangles = 0;
  double frame_ms = 0;  // refine + limit + render
  int frames = 0;
  std::string passes, failure;
  double peer_mtris = 0;
  std::string peer_failure;
};

// One warm-up frame, then up to `frames` timed ones within `budget_s` of wall time.
void time_frames(const ControlMesh& accepted, SubdivisionRule rule, int frames, double budget_s, Cell& c) {
  try {
    VulkanOptions options;
    options.render_width = 1024, options.render_height = 768;
    auto e = make_vulkan_evaluation(accepted, rule, c.depth, true, options);
    e->execute();
    std::vector<double> ms;
    std::optional<GpuTimes> times;
    const auto start = std::chrono::steady_clock::now();
    for (int f = 0; f < frames; ++f) {
      e->execute();
      times = e->gpu_times();
      if (!times) {
        c.failure = "the device's queue has no timestamps";
        return;
      }
      ms.push_back(times->kernel_ms);
      if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > budget_s) break;
    }
    c.frame_ms = median(ms);
    c.frames = static_cast<int>(ms.size());
    for (const GpuPassTime& p : times->passes)
      if (p.label != "upload") c.passes += (c.passes.empty() ? "" : "; ") + p.label + " " + fixed(p.ms, p.ms < 10 ? 2 : 1);
  } catch (const gpu::Unsupported& e) {
    c.failure = e.what();
  } catch (const gpu::Unavailable& e) {
    c.failure = e.what();
  } catch (const gpu::VulkanError& e) {
    c.failure = e.what();
  }
}

void time_peer(MeasureContext& context, const char* peer, const std::string& mesh, int reps, Cell& c) {
  MeasureOptions m;
  m.validate = false;
  m.hausdorff = false;
  m.reps = reps;
  const RunRow row = measure_run({peer, mesh, Backend::Cpu, c.depth}, m, context);
  if (row.status != RunStatus::Ok) c.peer_failure = std::string(to_string(row.status)) + ": " + row.message;
  else c.peer_mtris = row.triangle_rate_mtris;
}

struct Row {
  const Model* model;
  std::string shape, failure;
  std::vector<Cell> cells;
};

Row measure_row(MeasureContext& context, const Model& model, const char* scheme, const char* peer,
                const PaperTableOptions& o) {
  Row r{&model, "", "", {}};
  const SubdivisionRule rule = std::string(scheme) == "fragments-loop" ? SubdivisionRule::Loop : SubdivisionRule::CatmullClark;
  std::shared_ptr<const ControlMesh> accepted;
  try {
    accepted = context.accepted(model.mesh, *find_scheme(scheme));
  } catch (const InputError& e) {
    r.failure = e.what();
    return r;
  }
  const MeshFacts f = compute_facts(*accepted);
  r.shape = "(" + std::to_string(f.vertices) + " vertices, " + std::to_string(f.faces) +
            (rule == SubdivisionRule::Loop ? " triangles)" : " quads)");
  for (int depth : kDepths) {
    if (o.quick && depth > 4) break;
    Cell c;
    c.depth = depth;
    c.triangles = long(f.faces) << (2 * depth) << (rule == SubdivisionRule::Loop ? 0 : 1);
    std::fprintf(stderr, "shiue-loop-table1: %s %s depth %d\n", scheme, model.mesh, depth);
    time_frames(*accepted, rule, o.reps, o.quick ? 2.0 : 20.0, c);
    time_peer(context, peer, model.mesh, o.quick ? 1 : o.reps, c);
    r.cells.push_back(c);
  }
  return r;
}

std::string fps_of(const Cell& c) {
  if (!c.failure.empty()) return "—";
  const double fps = 1000.0 / c.frame_ms;
  return fixed(fps, fps < 10 ? 2 : fps < 100 ? 1 : 0);
}

void write_paper_table(std::ostringstream& md, const std::vector<Row>& loop) {
  std::vector<std::string> header = {"config"};
  for (const Model& m : kLoopModels)
    for (int d : kDepths) header.push_back(std::string(m.paper) + " d" + std::to_string(d));
  MarkdownTable t(header);
  for (int k = 0; k < 4; ++k) {
    std::vector<std::string> cells = {std::to_string(k + 1) + " (poster)"};
    for (double v : kPaperFps[k]) cells.push_back(fixed(v, 2));
    t.add_row(cells);
  }
  std::vector<std::string> ours = {"ours"};
  for (const Row& r : loop)
    for (size_t i = 0; i < std::size(kDepths); ++i) ours.push_back(i < r.cells.size() ? fps_of(r.cells[i]) : "—");
  ours.resize(header.size(), "—");  // models not measured (--quick)
  t.add_row(ours);
  t.write(md);
}

void write_detail(std::ostringstream& md, const char* scheme, const char* peer, const std::vector<Row>& rows) {
  MarkdownTable t({"scheme", "poster's model", "ours", "depth", "triangles", "fps", "M tri/s", std::string(peer) + " cpu M tri/s",
                   "ours / peer", "frames", "passes (ms)"});
  for (const Row& r : rows) {
    const std::string paper = r.model->paper ? r.model->paper : "(not in the poster)";
    if (!r.failure.empty()) {
      t.add_row({scheme, paper, std::string(r.model->mesh) + " (" + r.failure + ")", "—", "—", "—", "—", "—", "—", "—", "—"});
      continue;
    }
    for (const Cell& c : r.cells) {
      const bool ok = c.failure.empty();
      const double mtris = ok ? c.triangles / (c.frame_ms * 1e3) : 0;
      t.add_row({scheme, paper, std::string(r.model->mesh) + " " + r.shape, std::to_string(c.depth),
                 std::to_string(c.triangles), ok ? fps_of(c) : c.failure, ok ? fixed(mtris, 2) : "—",
                 c.peer_failure.empty() ? fixed(c.peer_mtris, 2) : c.peer_failure,
                 ok && c.peer_failure.empty() && c.peer_mtris > 0 ? fixed(mtris / c.peer_mtris, 3) : "—",
                 std::to_string(c.frames), c.passes});
    }
  }
  t.write(md);
}

int run_table1(const PaperTableOptions& o, std::ostream& out) {
  MeasureContext context(describe_machine());
  std::vector<Row> loop, quads;
  for (const Model& m : kLoopModels) {
    if (o.quick && loop.size() == 1) break;
    loop.push_back(measure_row(context, m, "fragments-loop", "osd-uniform-loop", o));
  }
  for (const Model& m : kQuadModels) {
    if (o.quick) break;
    quads.push_back(measure_row(context, m, "fragments-cc", "osd-uniform", o));
  }
  std::ostringstream md;
  md << "# shiue-loop-table1 — Loop subdivision with mesh fragments, Table 1 (frames per second)\n\n";
  md << "Device: " << device_line() << ".\n\n";
  md << "ours fps = 1000 / (gather + every refinement level + limit projection + drawing the output into a 1024 x 768 "
        "offscreen target), from Vulkan timestamps, median of up to "
     << o.reps
     << " frames after a warm-up frame; the control points' upload is not counted (the poster's models sit on the "
        "GPU). Stand-ins for the poster's models (not public): ";
  for (const Model& m : kLoopModels) md << m.paper << " = `" << m.mesh << "` (" << m.why << "); ";
  md << "all closed.\n\n";
  write_paper_table(md, loop);
  md << "\nEvery cell, with the CPU peer (OpenSubdiv's uniform refinement and limit projection at the same depth, "
        "one thread of "
     << context.machine().cpu_model << ") measured in the same run:\n\n";
  write_detail(md, "fragments-loop", "osd-uniform-loop", loop);
  if (!quads.empty()) {
    md << "\nThe same cells for Catmull-Clark fragments on quad meshes (not in the poster):\n\n";
    write_detail(md, "fragments-cc", "osd-uniform", quads);
  }
  if (o.quick) md << "\n(--quick: one model at depth 4.)\n";
  publish(o, "shiue-loop-table1", md.str(), out);
  return 0;
}

}  // namespace

std::vector<PaperTable> fragment_paper_tables() {
  return {{"shiue-loop-table1", "Loop subdivision with mesh fragments (poster), Table 1: frames per second at depth 4 and 5",
           run_table1}};
}

// The paper tables register here, with the experiments (sdb_scheme_fragments_paper), not with the
// algorithm: the plug-in library links no measurement (cmake/Schemes.cmake).
SDB_REGISTER_PAPER_TABLES(fragments, fragment_paper_tables);

}  // namespace sdb::fragments
