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
  // its largest valence is 720. Checked on the mesh as handed to prepare() (after quadrangulation,
  // where an n-gon becomes a valence-n vertex).
  int max_face_size = 64;
  int max_valence = 1024;
};

// How far a scheme's output may lie from its reference limit surface at the same SurfaceCoord,
// on every mesh it accepts at its default levels; a row past it is "failed". Negative: no bound
// (the figures are reported, not judged).
struct DeviationBound {
  double pos_rel_diag = -1;  // largest distance over the bounding-box diagonal
  double normal_deg = -1;    // largest angle between normals, where both are defined
};

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
  // False: the output has no SurfaceCoords (OpenMesh's subdividers do not say where a refined
  // vertex lies on the base mesh); rows then carry watertightness and Hausdorff distance only.
  bool surface_coords = true;
  // Meshes this scheme wants in the curated default set; the set is the union over all schemes,
  // and every scheme runs on every mesh of it that it accepts.
  std::vector<std::string> default_meshes;
  std::vector<HeadlineRun> headline_runs;
  std::vector<ParameterSpec> parameters;
};

struct RunRequest {
  Backend backend = Backend::Cpu;
  int level = 0;
  int threads = 0;  // cpu-mt: 0 means TBB's default
  Parameters parameters;  // every declared parameter, resolved (Parameters::resolve)
};

// A request with every parameter the scheme declares at its default.
RunRequest default_request(const SchemeInfo& info, Backend backend, int level, int threads = 0);

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
  // What the row should say of this output beside its figures (a limit the scheme could not take
  // exactly, say); empty: nothing. Recorded in the row's message.
  virtual std::string note() const { return {}; }
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
};

}  // namespace sdb
