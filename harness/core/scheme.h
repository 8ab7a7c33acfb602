// The Scheme interface: what every paper method and every peer implements, and SchemeInfo, the
// data through which the harness learns everything it needs of a scheme (what it accepts, which
// peer its rows are read against, its deviation bound, the meshes it wants in the default set,
// its parameters). The harness never includes a scheme's header.
//
// Split as OpenSubdiv splits Far from Osd: prepare() does everything that depends only on
// topology, level and backend (tables, patch indices, buffers, the output's triangles and
// SurfaceCoords), once and untimed; Evaluation::execute() is the per-frame work that benchmarks
// time: control positions in, positions and normals out. A scheme never prints or writes files.
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "harness/core/backend.h"
#include "harness/core/control_mesh.h"
#include "harness/core/gpu_times.h"
#include "harness/core/parameters.h"
#include "harness/core/tessellation.h"

namespace sdb {

// Recursive schemes take a depth k; patch schemes a rate N (N x N samples per base quad).
enum class LevelKind { Depth, Rate };

// Segments per base-face edge that a level stands for (depth k: 2^k; rate N: N - 1), recorded
// as `tessellation` so rows of recursive and patch schemes compare on equal output (-1 for a
// depth outside 0..30).
int segments_per_edge(LevelKind kind, int level);
// The level of `kind` that gives `segments` per edge, if there is one.
std::optional<int> level_for_segments(LevelKind kind, int segments);

struct MeshRequirements {
  enum class Faces { Any, QuadsOnly, TrianglesOnly };
  Faces faces = Faces::Any;
  bool quadrangulate = false;  // QuadsOnly: make quads by one Catmull-Clark step instead of refusing
  bool split_polygons = false;  // Any: split faces of more than four sides into quads and a triangle (split_polygons.h)
  bool manifold = true;        // no edge with more than two faces, consistent orientation
  bool closed = false;         // no boundary edges
  bool genus0 = false;
  bool creases = false;        // honours edge creases and corners (else refuses tagged meshes)
  bool holes = false;
  // Past these the libraries fail rather than refuse: OpenSubdiv segfaults on a 10,000-vertex face
  // and its Bfr and limit evaluation grow with the square of a face's size (a 1,000-gon: 16 s;
  // 2,000: over 100 s); Embree aborts past valence 64. The corpus's largest face has 6 vertices,
  // its largest valence is 360. Checked on the mesh as handed to prepare() (after quadrangulation,
  // where an n-gon becomes a valence-n vertex). Valence: the reference limit every run is judged
  // by (Bfr, refined to level 10 around the vertex) grows faster than the square of it, and at
  // valence 1000 a run took minutes (harness/bench/README.md, "Valence").
  int max_face_size = 64;
  int max_valence = 512;
};

// How far a scheme's output may lie from the limit surface of its input (at the same SurfaceCoord,
// or by nearest points where its vertices have none on the input), on every mesh it accepts at its
// default levels; a row past it is "failed". Negative: no bound (the figures are reported, not
// judged).
struct DeviationBound {
  double pos_rel_diag = -1;  // largest distance over the bounding-box diagonal
  double normal_deg = -1;    // largest angle between normals, where both are defined
};

// Whether a scheme's output lies on the limit surface of the mesh it was given or near it. Rows
// record which ("reproduces" | "approximates", limit_claim_of) and the report prints it.
enum class LimitClaim {
  // On the limit surface, within the scheme's bound.
  Reproduces,
  // On it once every semi-sharp crease and corner (finite sharpness) has decayed at the requested
  // depth, and near it before: Far's limit masks applied at a refined level treat a crease that is
  // still active as infinitely sharp (osd-uniform). Such rows approximate, and are not judged by
  // the bound, which is the promise of the rows that reproduce.
  ReproducesOnceSharpnessDecays,
  // Near it only: a surface fitted to it (geometry-image), a refined control mesh (OpenMesh,
  // mipgh-quadtri), a patch approximation (c-patches). The bound, when declared, is how near.
  Approximates,
};
std::string_view to_string(LimitClaim claim);

// In the registry's order: peers first, then methods, then test schemes.
enum class SchemeRole {
  Peer,    // what the methods are measured against (OpenSubdiv, Embree, OpenMesh)
  Method,  // a paper's method
  Test,    // compiled into the tests only
};
std::string_view to_string(SchemeRole role);

// A run a scheme wants in the default set whatever the output budget: the figures its README and
// notes quote. Its peer's run at the same mesh, backend and tessellation comes with it.
struct HeadlineRun {
  std::string mesh;
  Backend backend = Backend::Cpu;
  int level = 0;
};

struct SchemeInfo {
  std::string name;         // part of the CLI and results contract, e.g. "cpatch-2pass"
  std::string paper;        // short citation
  std::string description;  // one line
  SchemeRole role = SchemeRole::Method;
  SubdivisionRule reference = SubdivisionRule::CatmullClark;  // which OpenSubdiv limit it is judged by
  LevelKind level_kind = LevelKind::Rate;
  std::vector<Backend> backends;
  std::vector<int> default_levels;
  MeshRequirements accepts;
  // The scheme whose rows at the same mesh and tessellation (and backend, or cpu-mt where the
  // peer lacks it) this scheme's rows are read against: the report's ratio, the gate's unit.
  // Empty: none (the gate then uses the write-bandwidth probe of the same round).
  std::string peer;
  DeviationBound bound;
  LimitClaim limit = LimitClaim::Reproduces;
  // An integer parameter that at 0 makes the output the refined control points instead of their
  // limit (mipgh's `limit`): such rows approximate, and are not judged by the bound. Empty: none.
  std::string limit_projection_parameter;
  // For a scheme that subdivides a control mesh of its own (Tessellation::reference: the fitted
  // image's g0), how far the output may lie from that mesh's limit at its SurfaceCoords: the
  // scheme's exactness, judged beside its distance from the input's limit.
  DeviationBound own_bound;
  // False: the output has no SurfaceCoords (OpenMesh's subdividers do not say where a refined
  // vertex lies on the base mesh); rows then carry watertightness and Hausdorff distance only.
  bool surface_coords = true;
  // Meshes this scheme wants in the curated default set; the set is the union over all schemes,
  // and every scheme runs on every mesh of it that it accepts.
  std::vector<std::string> default_meshes;
  std::vector<HeadlineRun> headline_runs;
  // Meshes its large outputs are measured on (`subdivbench gpu-check`: 10-100 M triangles on a
  // GPU), in order of preference: a real mesh big enough that the output comes from many patches
  // at a moderate level. Empty: its headline runs' meshes, then its default meshes.
  std::vector<std::string> large_meshes;
  std::vector<ParameterSpec> parameters;
  // Peak memory per output triangle of a validated run (Scheme::estimated_peak_bytes): the
  // largest measured over the CPU schemes unless the scheme measured its own (fragments, MiPGH:
  // 171 and 181 bytes, harness/bench/notes/limits-2026-12-07.md). At the default the sword's
  // 45.8 M-triangle depth 4, the issues' headline size, was refused on a 24 GB machine.
  double peak_bytes_per_triangle = 512;
};

struct RunRequest {
  Backend backend = Backend::Cpu;
  int level = 0;
  int threads = 0;  // cpu-mt: 0 means TBB's default
  Parameters parameters;  // every declared parameter, resolved (Parameters::resolve)
};

// A request with every parameter the scheme declares at its default.
RunRequest default_request(const SchemeInfo& info, Backend backend, int level, int threads = 0);

// Whether a run reproduces its input's limit surface or approximates it (SchemeInfo::limit): a
// scheme that reproduces it once sharpness decays approximates at a depth no greater than the
// input's largest finite sharpness (Sdc: below 10, sharpness decays by one per level), and one
// whose limit projection is switched off approximates.
bool reproduces_limit(const SchemeInfo& info, const RunRequest& request, const ControlMesh& mesh);

class Evaluation {
 public:
  virtual ~Evaluation() = default;
  // The timed work; may be called many times.
  virtual void execute() = 0;
  // Output of the last execute(). GPU backends read back here, outside the timed work.
  virtual const Tessellation& result() = 0;
  // Bytes the evaluation writes per execute() (its output buffers), for the bandwidth bound.
  virtual size_t bytes_out() const = 0;
  virtual std::optional<GpuTimes> gpu_times() const { return std::nullopt; }
  // What the row should say besides its figures, one sentence each: how prepare() came by its
  // input when that is news (a cached geometry image refused and refitted), a limit the scheme
  // could not take exactly (semi-sharp creases left at the depth). A scheme never prints.
  virtual std::vector<std::string> notes() const { return {}; }
};

class Scheme {
 public:
  virtual ~Scheme() = default;
  virtual const SchemeInfo& info() const = 0;
  // Why this request cannot run (a level out of range, a backend it lacks, a device limit), or
  // nullopt. Declined requests are "unsupported" rows.
  virtual std::optional<std::string> unsupported(const RunRequest&) const { return std::nullopt; }
  // `mesh` has passed accept_mesh() for this scheme and the request was not declined. Throws
  // InputError for meshes it refuses late, Unsupported for a device or size limit it runs into.
  virtual std::unique_ptr<Evaluation> prepare(const ControlMesh& mesh, const RunRequest& request) const = 0;
  // Output size of a request, for run budgets. The default counts samples per base face: a quad
  // gives 2 s^2 triangles, a Loop triangle s^2, an n-gon's n sub-quads n s^2 / 2 (s = segments).
  virtual long estimated_triangles(const ControlMesh& accepted, const RunRequest& request) const;
  // Memory a run of the request takes at its peak, prepare and validation included, for run
  // budgets: a run refused up front instead of ending in bad_alloc. The default: the output's
  // estimated triangles at SchemeInfo::peak_bytes_per_triangle; a scheme whose preparation
  // allocates more (a geometry image's fit) says so here.
  virtual double estimated_peak_bytes(const ControlMesh& accepted, const RunRequest& request) const;
};


}  // namespace sdb
