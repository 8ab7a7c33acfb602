// The Scheme interface: what every paper method and every peer implements.
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

#include "control_mesh.h"
#include "osd_topology.h"
#include "tessellation.h"

namespace sdb {

enum class Backend { Cpu, CpuMt, Vulkan };
std::string_view to_string(Backend b);
std::optional<Backend> parse_backend(std::string_view s);

// Recursive schemes take a depth k; patch schemes a rate N (N x N samples per base quad).
enum class LevelKind { Depth, Rate };

struct MeshRequirements {
  enum class Faces { Any, QuadsOnly, TrianglesOnly };
  Faces faces = Faces::Any;
  bool quadrangulate = false;  // QuadsOnly: make quads by one Catmull-Clark step instead of refusing
  bool manifold = true;        // no edge with more than two faces, consistent orientation
  bool closed = false;         // no boundary edges
  bool genus0 = false;
  bool creases = false;        // honours edge creases and corners (else refuses tagged meshes)
  bool holes = false;
};

struct SchemeInfo {
  std::string name;         // part of the CLI and results contract, e.g. "cpatch-2pass"
  std::string paper;        // short citation
  std::string description;  // one line
  SubdivisionRule reference = SubdivisionRule::CatmullClark;  // which OpenSubdiv limit it is judged by
  LevelKind level_kind = LevelKind::Rate;
  std::vector<Backend> backends;
  std::vector<int> default_levels;
  MeshRequirements accepts;
};

// Segments per base-face edge that a level stands for (depth k: 2^k; rate N: N - 1), recorded
// as `tessellation` so rows of recursive and patch schemes compare on equal output.
int segments_per_edge(LevelKind kind, int level);

struct GpuPassTime {
  std::string label;
  double ms = 0.0;
};

// Vulkan timestamp figures of the last execute() (and result(), for readback).
struct GpuTimes {
  double upload_ms = 0.0;
  double kernel_ms = 0.0;  // sum of the compute / draw passes
  double readback_ms = 0.0;
  std::vector<GpuPassTime> passes;
};

struct RunRequest {
  Backend backend = Backend::Cpu;
  int level = 0;
  int threads = 0;  // cpu-mt: 0 means TBB's default
};

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
};

class Scheme {
 public:
  virtual ~Scheme() = default;
  virtual const SchemeInfo& info() const = 0;
  // Why this request cannot run (a level beyond a device limit, say), or nullopt.
  virtual std::optional<std::string> unsupported(const RunRequest&) const { return std::nullopt; }
  // `mesh` has passed accept_mesh() for this scheme. Throws InputError for meshes it refuses late.
  virtual std::unique_ptr<Evaluation> prepare(const ControlMesh& mesh, const RunRequest& request) const = 0;
  // Output size of a request, for run budgets. The default counts samples per base face: a quad
  // gives 2 s^2 triangles, a Loop triangle s^2, an n-gon's n sub-quads n s^2 / 2 (s = segments).
  virtual long estimated_triangles(const ControlMesh& accepted, const RunRequest& request) const;
};

// Checks a mesh against a scheme's requirements: returns the mesh to hand to prepare() (quadrangulated
// when the scheme asks for quads and allows it) or throws InputError saying why the scheme refuses it.
ControlMesh accept_mesh(const ControlMesh& mesh, const SchemeInfo& info);

}  // namespace sdb
