// ni2008-table4 (2-pass) and ni2008-table5 (1-pass): frames per second of the c-patch Vulkan
// variants in render mode (conversion + evaluation + rasterization into a 1024 x 768 offscreen
// target, from GPU timestamps), beside the paper's, with our triangle rate and its ratio to the
// osd-bfr CPU peer measured in the same run.
#include <algorithm>
#include <chrono>
#include <map>
#include <sstream>

#include "harness/core/errors.h"
#include "harness/core/registry.h"
#include "harness/gpu/errors.h"
#include "harness/gpu/gpu.h"
#include "harness/results/markdown.h"
#include "harness/results/statistics.h"
#include "schemes/cpatch/paper/paper.h"
#include "schemes/cpatch/vulkan.h"

namespace sdb::cpatch {
namespace {

struct PaperRow {
  std::string paper_label;          // the paper's model; empty for meshes the paper did not show
  std::string mesh;                 // ours
  std::map<int, double> paper_fps;  // by N
};

struct FpsTableSpec {
  std::string id, title;
  GpuVariant variant;
  std::vector<int> rates;
  std::vector<PaperRow> rows;
  GpuVariant companion;  // timed at the same N too, for comparison
  std::string notes;     // Markdown after the tables
};

// The corpus meshes both tables add to the paper's models.
const char* kCorpus[] = {"stein/sword_quad_dominant", "crane/spot_control", "crane/blub_control", "pmp/fandisk_quads"};

// Outputs beyond this many triangles are not asked of the CPU peer: osd-bfr's Tessellation would
// take several GiB on a shared development machine, and a frame tens of seconds.
constexpr long kMaxPeerTriangles = 60'000'000;

struct FrameTiming {
  double median_ms = 0;
  int frames = 0;
  std::string passes;   // the last frame's passes, "label ms; ..."
  std::string failure;  // why there is no timing
};


// A software rasterizer (lavapipe) shades vertices on one thread: the sword at N = 33 (183 M
// triangles) did not finish a frame within the 600 s fence wait. Such cells are not asked of it.
constexpr long kMaxSoftwareRenderTriangles = 60'000'000;

// Render mode: one warm-up frame, then `frames` timed frames, fewer once `budget_s` of wall time
// has passed (at least one). The time of a frame is its kernel time: conversion passes and the
// render pass; the control-point upload is excluded (the paper's models are static on the GPU).
FrameTiming time_render(const ControlMesh& quads, int rate, GpuVariant variant, int frames, double budget_s) {
  FrameTiming t;
  if (auto why = vulkan_unsupported(variant, GpuMode::Render, rate)) {
    t.failure = *why;
    return t;
  }
  const long triangles = 2L * num_faces(quads) * (rate - 1) * (rate - 1);
  if (triangles > kMaxSoftwareRenderTriangles && gpu::probe().type == gpu::DeviceType::Cpu) {
    t.failure = "not run (" + fixed(triangles / 1e6, 0) + " M triangles on a software rasterizer)";
    return t;
  }
  try {
    GpuOptions options;
    options.variant = variant;
    options.mode = GpuMode::Render;
    CpatchVulkan renderer(quads, rate, options);
    renderer.execute();
    std::vector<double> ms;
    const auto start = std::chrono::steady_clock::now();
    std::optional<GpuTimes> times;
    for (int f = 0; f < frames; ++f) {
      renderer.execute();
      times = renderer.gpu_times();
      if (!times) {
        t.failure = "the device's queue has no timestamps";
        return t;
      }
      ms.push_back(times->kernel_ms);
      if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > budget_s) break;
    }
    t.median_ms = median(ms);
    t.frames = static_cast<int>(ms.size());
    for (const GpuPassTime& p : times->passes)
      t.passes += (t.passes.empty() ? "" : "; ") + p.label + " " + fixed(p.ms, p.ms < 10 ? 2 : 1);
  } catch (const gpu::Unsupported& e) {
    t.failure = e.what();
  } catch (const gpu::Unavailable& e) {
    t.failure = e.what();
  } catch (const gpu::VulkanError& e) {  // a frame past the fence timeout: the table goes on
    t.failure = e.what();
  }
  return t;
}

struct PeerRate {
  double mtris = 0;
  std::string failure;
};

// osd-bfr on the cpu backend (one thread), the same mesh as given and the same rate N.
PeerRate peer_rate(MeasureContext& context, const std::string& mesh, int rate, int reps, long triangles) {
  if (triangles > kMaxPeerTriangles)
    return {0, "not run (" + fixed(triangles / 1e6, 0) + " M triangles, beyond this table's peer budget)"};
  MeasureOptions m;
  m.validate = false;
  m.hausdorff = false;
  m.reps = triangles > 10'000'000 ? 1 : reps;
  m.min_time_s = triangles > 10'000'000 ? 0.001 : 0.05;
  const RunRow row = measure_run({"osd-bfr", mesh, Backend::Cpu, rate}, m, context);
  if (row.status != RunStatus::Ok) return {0, std::string(to_string(row.status)) + ": " + row.message};
  return {row.triangle_rate_mtris, ""};
}

std::string fps_text(double ms) {
  const double fps = 1000.0 / ms;
  return fixed(fps, fps < 10 ? 2 : fps < 100 ? 1 : 0);
}

struct Cell {
  int rate = 0;
  long triangles = 0;
  FrameTiming ours, companion;
  PeerRate peer;
};

struct RowResult {
  const PaperRow* row = nullptr;
  std::string shape;  // (verts, quads, eqs)
  int quads = 0;
  std::vector<Cell> cells;
  std::string failure;  // the mesh could not be loaded
};

RowResult measure_row(const FpsTableSpec& spec, const PaperRow& row, const std::vector<int>& rates,
                      const PaperTableOptions& o, MeasureContext& context) {
  RowResult r;
  r.row = &row;
  std::shared_ptr<const ControlMesh> quads;
  try {
    quads = context.accepted(row.mesh, *find_scheme(scheme_name(spec.variant)));
  } catch (const InputError& e) {
    r.failure = e.what();
    return r;
  }
  r.shape = mesh_shape(context, row.mesh, *quads);
  r.quads = num_faces(*quads);
  const double budget_s = o.quick ? 2.0 : 20.0;
  for (int rate : rates) {
    Cell c;
    c.rate = rate;
    c.triangles = 2L * r.quads * (rate - 1) * (rate - 1);
    std::fprintf(stderr, "%s: %s N=%d (%ld triangles)\n", spec.id.c_str(), row.mesh.c_str(), rate, c.triangles);
    c.ours = time_render(*quads, rate, spec.variant, o.reps, budget_s);
    c.companion = time_render(*quads, rate, spec.companion, o.reps, budget_s);
    c.peer = peer_rate(context, row.mesh, rate, o.reps, c.triangles);
    r.cells.push_back(c);
  }
  return r;
}

std::string paper_cell(const PaperRow& row, int rate) {
  const auto it = row.paper_fps.find(rate);
  return it == row.paper_fps.end() ? "—" : fixed(it->second, 0);
}

std::string ours_cell(const FrameTiming& t) { return t.failure.empty() ? fps_text(t.median_ms) : "—"; }

// The paper's layout: a row per mesh, "paper / ours" fps per N.
void write_wide_table(std::ostringstream& md, const std::vector<int>& rates, const std::vector<RowResult>& rows) {
  std::vector<std::string> header = {"mesh (verts, quads, eqs)", "ours"};
  for (int rate : rates) header.push_back("N = " + std::to_string(rate) + " paper / ours");
  MarkdownTable table(header);
  for (const RowResult& r : rows) {
    std::vector<std::string> cells = {r.row->paper_label.empty() ? "(not in the paper)" : r.row->paper_label,
                                      r.row->mesh + " " + (r.failure.empty() ? r.shape : "(" + r.failure + ")")};
    for (size_t k = 0; k < rates.size(); ++k)
      cells.push_back(paper_cell(*r.row, rates[k]) + " / " + (k < r.cells.size() ? ours_cell(r.cells[k].ours) : "—"));
    table.add_row(cells);
  }
  table.write(md);
}

// Every cell with what it is made of: triangles, rates, the CPU peer, the companion variant, passes.
void write_detail_table(std::ostringstream& md, const FpsTableSpec& spec, const std::vector<RowResult>& rows) {
  MarkdownTable table({"mesh", "quads", "N", "triangles", "paper fps", "ours fps", "ours M tri/s", "osd-bfr cpu M tri/s",
                       "ours / osd-bfr", std::string(scheme_name(spec.companion)) + " fps", "frames", "passes of the last frame (ms)"});
  for (const RowResult& r : rows) {
    if (!r.failure.empty()) {
      table.add_row({r.row->mesh, "—", "—", "—", "—", r.failure});
      continue;
    }
    for (const Cell& c : r.cells) {
      const bool ok = c.ours.failure.empty();
      const double mtris = ok ? c.triangles / (c.ours.median_ms * 1e3) : 0;
      table.add_row({r.row->mesh, std::to_string(r.quads), std::to_string(c.rate), std::to_string(c.triangles),
                     paper_cell(*r.row, c.rate), ok ? fps_text(c.ours.median_ms) : c.ours.failure,
                     ok ? fixed(mtris, 1) : "—", c.peer.failure.empty() ? fixed(c.peer.mtris, 1) : c.peer.failure,
                     ok && c.peer.failure.empty() && c.peer.mtris > 0 ? fixed(mtris / c.peer.mtris, 2) : "—",
                     c.companion.failure.empty() ? fps_text(c.companion.median_ms) : c.companion.failure,
                     std::to_string(c.ours.frames), c.ours.passes});
    }
  }
  table.write(md);
}

int run_fps_table(const FpsTableSpec& spec, const PaperTableOptions& o, std::ostream& out) {
  MeasureContext context(describe_machine());
  // --quick: the two smallest stand-ins at the two smallest rates, for tests.
  std::vector<PaperRow> rows = spec.rows;
  std::vector<int> rates = spec.rates;
  if (o.quick) {
    rows.resize(std::min<size_t>(rows.size(), 2));
    rates.resize(2);
  }
  std::vector<RowResult> results;
  for (const PaperRow& row : rows) results.push_back(measure_row(spec, row, rates, o, context));

  std::ostringstream md;
  md << "# " << spec.id << " — " << spec.title << "\n\n";
  md << "Device: " << device_line() << ".\n\n";
  md << "CPU peer: `osd-bfr` (OpenSubdiv Bfr tessellation of the mesh as given, same N) on the `cpu` backend (one "
        "thread) of "
     << context.machine().cpu_model << ", measured in the same run.\n\n";
  md << "ours fps = 1000 / (conversion + evaluation + rasterization into a 1024 x 768 offscreen target), from GPU "
        "timestamps, median of up to "
     << o.reps
     << " frames after a warm-up frame; the upload of the control points is not included (the paper's models "
        "sit on the GPU). Triangles per second = 2 (N-1)^2 quads x fps. Stand-ins (TABLES.md): random quad meshes "
        "with the paper's quad counts and extraordinary shares.\n\n";
  write_wide_table(md, rates, results);
  md << "\n";
  write_detail_table(md, spec, results);
  md << "\n" << spec.notes;
  if (o.quick) md << "\n(--quick: a subset of meshes and rates.)\n";
  publish(o, spec.id, md.str(), out);
  return 0;
}

std::vector<PaperRow> with_corpus(std::vector<PaperRow> rows) {
  for (const char* mesh : kCorpus) rows.push_back({"", mesh, {}});
  return rows;
}

// Table 4's frog party: nine frogs at N = 9, the paper's 50 fps (about one million polygons).
std::string frog_party_note(const PaperTableOptions& o) {
  MeasureContext context(describe_machine());
  const auto quads = context.accepted("frog-party", *find_scheme("cpatch-2pass"));
  const FrameTiming t = time_render(*quads, 9, GpuVariant::TwoPass, o.reps, o.quick ? 2.0 : 20.0);
  const long triangles = 2L * num_faces(*quads) * 64;
  std::string s = "Frog Party (nine frogs, 9 x 1292 quads, 59% extraordinary, N = 9, " + std::to_string(triangles) +
                  " triangles): paper 50 fps on its GPU; ours (frog-party) ";
  s += t.failure.empty() ? fps_text(t.median_ms) + " fps, " + fixed(triangles / (t.median_ms * 1e3), 1) + " M triangles/s"
                         : t.failure;
  s += ". The paper measured Bunnell's adaptive Catmull-Clark subdivision on one frog at depth 3 at 44 fps on the same "
       "hardware.\n";
  return s;
}

}  // namespace

int run_table4(const PaperTableOptions& o, std::ostream& out) {
  FpsTableSpec spec;
  spec.id = "ni2008-table4";
  spec.title = "GPU Smoothing of Quad Meshes, Table 4 (2-pass: convert, then evaluate and render)";
  spec.variant = GpuVariant::TwoPass;
  spec.companion = GpuVariant::Tessellation;
  spec.rates = {5, 9, 17, 33};
  spec.rows = with_corpus({{"Sword (140, 138, 38%)", "sword-standin", {{5, 965}, {9, 965}, {17, 965}, {33, 703}}},
                           {"Head (602, 600, 100%)", "head-standin", {{5, 637}, {9, 557}, {17, 376}, {33, 165}}},
                           {"Frog (1308, 1292, 59%)", "frog-standin", {{5, 483}, {9, 392}, {17, 226}, {33, 87}}}});
  spec.notes = o.quick ? "" : frog_party_note(o);
  spec.notes += "\ncpatch-tess: Table 2 in the tessellation control stage, the hardware tessellator amplifies, the "
                "evaluation stage evaluates (the paper's Section 6 outlook).\n";
  return run_fps_table(spec, o, out);
}

int run_table5(const PaperTableOptions& o, std::ostream& out) {
  FpsTableSpec spec;
  spec.id = "ni2008-table5";
  spec.title = "GPU Smoothing of Quad Meshes, Table 5 (1-pass: the geometry shader converts and evaluates)";
  spec.variant = GpuVariant::OnePass;
  spec.companion = GpuVariant::TwoPass;
  spec.rates = {2, 5, 8};
  spec.rows = with_corpus({{"Sword (140, 138, 38%)", "sword-standin", {{2, 389}, {5, 96}, {8, 43}}},
                           {"Head (602, 600, 100%)", "head-standin", {{2, 108}, {5, 34}, {8, 15}}},
                           {"Frog (1308, 1292, 59%)", "frog-standin", {{2, 44}, {5, 10}, {8, 4}}}});
  spec.notes = "The geometry shader emits 2 N (N - 1) vertices of " + std::to_string(kOnePassComponents) +
               " components (clip position, view normal) per quad; the paper's DX10 limit allowed N <= 8.";
  if (const gpu::DeviceInfo info = gpu::probe(); info.available)
    spec.notes += " On " + info.name + " (maxGeometryOutputVertices " +
                  std::to_string(info.limits.max_geometry_output_vertices) + ", maxGeometryTotalOutputComponents " +
                  std::to_string(info.limits.max_geometry_total_output_components) +
                  ") the largest N is " + std::to_string(onepass_max_rate(info.limits)) + ".";
  spec.notes += "\n";
  return run_fps_table(spec, o, out);
}

}  // namespace sdb::cpatch
