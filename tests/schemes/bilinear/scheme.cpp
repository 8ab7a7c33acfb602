#include <algorithm>
#include <cstdlib>

#include "harness/core/errors.h"
#include "harness/core/registry.h"
#include "tests/schemes/bilinear/bilinear.h"
#include "tests/schemes/bilinear/cpu.h"

namespace sdb {
namespace {

class BilinearLimitScheme final : public Scheme {
 public:
  BilinearLimitScheme() {
    info_.name = "bilinear-limit";
    info_.paper = "test scheme: limit corners joined bilinearly";
    info_.description = "the limit points at the corners of every quad, interpolated bilinearly at rate N";
    info_.role = SchemeRole::Test;
    info_.reference = SubdivisionRule::CatmullClark;
    info_.level_kind = LevelKind::Rate;
    info_.backends = {Backend::Cpu, Backend::CpuMt};
    info_.default_levels = {2, 5, 9};
    info_.accepts.faces = MeshRequirements::Faces::QuadsOnly;
    info_.accepts.quadrangulate = true;
    info_.accepts.creases = true;
    info_.peer = "osd-bfr";
    // Flat quads against a curved limit, measured at N = 9 over the conformance meshes: 9.8% of
    // the diagonal on the cube (6 quads for a sphere), normals 67 degrees on Blub.
    info_.bound = {0.12, 75};
    // A typed parameter for the tests of the parameter machinery (--scheme bilinear-limit:repeat=2).
    info_.parameters = {{"repeat", "executions of the interpolation per execute()", true, 1, 1, 8, 0}};
  }
  const SchemeInfo& info() const override { return info_; }
  std::optional<std::string> unsupported(const RunRequest& r) const override {
    if (r.level < 2 || r.level > 129) return "rate N must be 2..129";
    if (r.backend == Backend::Vulkan) return "bilinear-limit runs on the CPU only";
    return std::nullopt;
  }
  std::unique_ptr<Evaluation> prepare(const ControlMesh& mesh, const RunRequest& r) const override {
    // $SDB_BILINEAR_SLOWDOWN (a factor) plants a slowdown under the same run name: the gate's test
    // (tests/gate_test.cpp) checks that both gates catch it. Test-only code, like the scheme.
    const char* slowdown = std::getenv("SDB_BILINEAR_SLOWDOWN");
    const int factor = slowdown ? std::max(1, std::atoi(slowdown)) : 1;
    return std::make_unique<bilinear::BilinearEvaluation>(mesh, r.level, r.backend == Backend::CpuMt,
                                                          factor * r.parameters.integer("repeat"));
  }

 private:
  SchemeInfo info_;
};

std::vector<std::unique_ptr<Scheme>> make_schemes() {
  std::vector<std::unique_ptr<Scheme>> s;
  s.push_back(make_bilinear_limit_scheme());
  return s;
}

}  // namespace

std::unique_ptr<Scheme> make_bilinear_limit_scheme() { return std::make_unique<BilinearLimitScheme>(); }

SDB_REGISTER_SCHEMES(bilinear, make_schemes);

}  // namespace sdb
