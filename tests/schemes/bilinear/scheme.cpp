#include <algorithm>
#include <csignal>
#include <cstdlib>

#include "harness/core/errors.h"
#include "harness/core/registry.h"
#include "bilinear.h"
#include "cpu.h"

namespace sdb {
namespace {

// crash: 1 and 2 a segmentation fault, 3 and 4 abort().
[[noreturn]] void die(int crash) {
  if (crash <= 2) std::raise(SIGSEGV);
  std::abort();
}

// Dies in execute(), as a library's kernel might.
class DyingEvaluation final : public Evaluation {
 public:
  DyingEvaluation(std::unique_ptr<Evaluation> inner, int crash) : inner_(std::move(inner)), crash_(crash) {}
  void execute() override { die(crash_); }
  const Tessellation& result() override { return inner_->result(); }
  size_t bytes_out() const override { return inner_->bytes_out(); }

 private:
  std::unique_ptr<Evaluation> inner_;
  int crash_;
};

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
    info_.limit = LimitClaim::Approximates;
    // A typed parameter for the tests of the parameter machinery (--scheme bilinear-limit:repeat=2).
    info_.parameters = {{"repeat", "executions of the interpolation per execute()", true, 1, 1, 8, 0},
                        {"crash", "test only: 1 SIGSEGV in prepare, 2 SIGSEGV in execute, 3 abort() in prepare, 4 abort() in execute",
                         true, 0, 0, 4, 0}};
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
    // `crash` plants what a library's bug does to the process, for the tests of run's crash
    // isolation (tests/isolation_test.cpp).
    const int crash = r.parameters.integer("crash");
    if (crash == 1 || crash == 3) die(crash);
    auto e = std::make_unique<bilinear::BilinearEvaluation>(mesh, r.level, r.backend == Backend::CpuMt,
                                                            factor * r.parameters.integer("repeat"));
    if (crash == 0) return e;
    return std::make_unique<DyingEvaluation>(std::move(e), crash);
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
