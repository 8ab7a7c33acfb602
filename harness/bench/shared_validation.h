// One validation per output content: a scheme's cpu, cpu-mt and vulkan rows often write the same
// bytes (the same arithmetic on every backend), and validating each (ray cracks, the deviation
// from the input's limit, open edges) computed the same figures up to three times. A row whose
// output equals an earlier row's byte for byte, of the same scheme, mesh and level (so judged
// against the same surfaces and by the same bounds), takes that row's verdict and names it
// (RunRow::validation_of). Bytes are compared, never a hash alone: a row is validated on its own
// output or on an output proven identical.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "harness/core/tessellation.h"
#include "harness/results/results.h"

namespace sdb {

// What validating one output found: the figures, whether a check failed, and what the
// validation said (appended to the row's message).
struct Verdict {
  WatertightFigures watertight;
  DeviationFigures deviation;
  bool failed = false;
  std::string message;
};

// The validation's result on a blank row: merged into `row` (its figures replaced, its status
// failed where the verdict is, the verdict's words after the row's own).
void apply_verdict(RunRow& row, const Verdict& verdict);

// What a validation reads besides the output: the surfaces it is judged against and the bounds
// that judge it. Two rows with equal subjects and equal output bytes get the same verdict.
struct VerdictSubject {
  std::string spec, mesh;  // the scheme as spelled (its parameters included) and the mesh
  int level = 0;
  const void* input = nullptr;  // the judged surfaces (JudgedSurfaces' meshes), by identity
  const void* accepted = nullptr;
  DeviationBound bound, own_bound;
  // What the validation was asked to compute (rays and their seed, Hausdorff, the unjudged
  // deviation: MeasureOptions): a verdict-only run does not take a full run's figures, nor the other way.
  std::string checks;
};

// Outputs validated in this run, kept whole for the byte comparison. Only one scheme+mesh's
// outputs are kept at a time (a plan runs a scheme's backends and levels on a mesh one after
// another), at most kKeptBytes of them: a summary cell of 2 M triangles is about 60 MB; a
// headline run of 46 M triangles is validated on each backend rather than copied.
class ValidatedOutputs {
 public:
  struct Earlier {
    std::string run;  // the row's name
    Verdict verdict;
  };
  // The earlier row whose subject is `subject` and whose output is `output` byte for byte.
  const Earlier* find(const VerdictSubject& subject, const Tessellation& output) const;
  // Keeps `output` (copied) and its verdict; forgets the outputs of another scheme or mesh.
  void remember(const VerdictSubject& subject, const Tessellation& output, std::string run, Verdict verdict);
  size_t size() const { return kept_.size(); }
  static constexpr size_t kKeptBytes = size_t(256) << 20;

 private:
  struct Kept {
    VerdictSubject subject;
    Tessellation output;
    Earlier earlier;
  };
  std::vector<Kept> kept_;
};

// Whether two outputs are the same bytes: positions, normals, triangles, coords, and the control
// mesh their coords refer to (the same object or the same content).
bool same_output(const Tessellation& a, const Tessellation& b);

// The bytes of an output's arrays (what keeping a copy of it costs).
size_t output_bytes(const Tessellation& t);

}  // namespace sdb
