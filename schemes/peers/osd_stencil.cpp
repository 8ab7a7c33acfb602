// osd-stencil, osd-stencil-loop: OpenSubdiv's fast CPU path as production code uses it: limit
// stencils made once per topology in prepare (limit_stencils.h), then every frame Osd::CpuEvaluator::EvalStencils (cpu)
// on TBB ranges of 200 stencils (cpu-mt: what Osd::TbbEvaluator does; Debian's libosdCPU lacks it),
// or with `osd-stencil:omp=1` Osd::OmpEvaluator::EvalStencils (cpu-mt, OpenMP), positions and both
// tangents, normals crossed from the tangents. TBB ranges are the default because OmpEvaluator's
// per-thread scratch (3 floats per thread, side by side: ompKernel.cpp) puts every thread's sums
// in one cache line, and on two threads it runs slower than CpuEvaluator on one (README.md).
#include <opensubdiv/osd/cpuEvaluator.h>
#include <opensubdiv/osd/ompEvaluator.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "schemes/peers/limit_stencils.h"
#include "schemes/peers/peers.h"

namespace sdb {
namespace {

namespace Far = OpenSubdiv::Far;
namespace Osd = OpenSubdiv::Osd;

static_assert(sizeof(Point3) == 3 * sizeof(float), "Point3 arrays are read as xyz float arrays");

class OsdStencilEvaluation final : public Evaluation {
 public:
  enum class Threads { One, OpenMp, TbbRanges };

  OsdStencilEvaluation(const ControlMesh& mesh, SubdivisionRule rule, int depth, Threads threads)
      : control_(mesh), threads_(threads) {
    PreparedStencils prepared = limit_stencils(mesh, rule, depth);
    stencils_ = std::move(prepared.stencils);
    out_ = std::move(prepared.topology);
    const size_t n = out_.coords.size();
    out_.positions.resize(n);
    out_.normals.resize(n);
    du_.resize(3 * n);
    dv_.resize(3 * n);
    if (!stencils_->all_vertices_have_limits())
      for (auto* v : {&dense_p_, &dense_du_, &dense_dv_}) v->resize(3 * stencils_->limit_vertices.size());
  }

  void execute() override {
    const Far::LimitStencilTable& t = *stencils_->table;
    const float* in = control_.positions[0].data();
    float* p = out_.positions[0].data();
    // Straight into the output when every vertex has a limit patch; else densely, then scattered.
    const bool direct = stencils_->all_vertices_have_limits();
    float* dp = direct ? p : dense_p_.data();
    float* du = direct ? du_.data() : dense_du_.data();
    float* dv = direct ? dv_.data() : dense_dv_.data();
    evaluate_stencils(t, in, dp, du, dv);
    if (!direct) {
      scatter_limit(*stencils_, dp, p);
      scatter_limit(*stencils_, du, du_.data());
      scatter_limit(*stencils_, dv, dv_.data());
      evaluate_refined_only(*stencils_, in, p, du_.data(), dv_.data());
    }
    const size_t vertices = out_.positions.size();
    if (threads_ != Threads::One)
      tbb::parallel_for(tbb::blocked_range<size_t>(0, vertices, 4096), [&](const tbb::blocked_range<size_t>& r) {
        normals_from_tangents(du_.data(), dv_.data(), out_.normals.data(), r.begin(), r.end());
      });
    else
      normals_from_tangents(du_.data(), dv_.data(), out_.normals.data(), 0, vertices);
  }

  const Tessellation& result() override { return out_; }
  size_t bytes_out() const override { return out_.positions.size() * 2 * sizeof(Point3); }

 private:
  void evaluate_stencils(const Far::LimitStencilTable& t, const float* in, float* p, float* du, float* dv) const {
    const Osd::BufferDescriptor desc(0, 3, 3);
    const int* sizes = &t.GetSizes()[0];
    const Far::Index* offsets = &t.GetOffsets()[0];
    const Far::Index* indices = &t.GetControlIndices()[0];
    const float *w = &t.GetWeights()[0], *wu = &t.GetDuWeights()[0], *wv = &t.GetDvWeights()[0];
    const int n = t.GetNumStencils();
    switch (threads_) {
      case Threads::One:
        Osd::CpuEvaluator::EvalStencils(in, desc, p, desc, du, desc, dv, desc, sizes, offsets, indices, w, wu, wv, 0, n);
        break;
      case Threads::OpenMp:
        Osd::OmpEvaluator::EvalStencils(in, desc, p, desc, du, desc, dv, desc, sizes, offsets, indices, w, wu, wv, 0, n);
        break;
      case Threads::TbbRanges:
        // The serial kernel writes stencil `begin` to dst[0]: each range gets its own slots.
        tbb::parallel_for(tbb::blocked_range<int>(0, n, 200), [&](const tbb::blocked_range<int>& r) {
          const size_t at = 3 * size_t(r.begin());
          Osd::CpuEvaluator::EvalStencils(in, desc, p + at, desc, du + at, desc, dv + at, desc, sizes, offsets, indices, w,
                                          wu, wv, r.begin(), r.end());
        });
        break;
    }
  }

  const ControlMesh control_;
  std::shared_ptr<const LimitStencils> stencils_;  // shared with other runs of the topology
  Threads threads_;
  std::vector<float> du_, dv_;
  std::vector<float> dense_p_, dense_du_, dense_dv_;  // per limit stencil, when some vertices have none
  Tessellation out_;
};

class OsdStencil final : public Scheme {
 public:
  explicit OsdStencil(SubdivisionRule rule) : rule_(rule), info_(limit_stencil_info(rule)) {
    const bool loop = rule == SubdivisionRule::Loop;
    info_.name = loop ? "osd-stencil-loop" : "osd-stencil";
    info_.paper = "peer: OpenSubdiv 3.5 Far::LimitStencilTable + Osd::CpuEvaluator / OmpEvaluator";
    info_.description = std::string(loop ? "Loop" : "Catmull-Clark") +
                        " limit stencils at the vertices of depth-k refinement, evaluated per frame";
    info_.peer = loop ? "osd-bfr-loop" : "osd-bfr";  // the same 2^k segments
    info_.backends = {Backend::Cpu, Backend::CpuMt};
    info_.parameters = {{"omp",
                         "cpu-mt: 1 evaluates with Osd::OmpEvaluator, 0 with CpuEvaluator on TBB ranges (what "
                         "Osd::TbbEvaluator, absent from Debian's package, does)",
                         true, 0, 0, 1, 1}};
  }
  const SchemeInfo& info() const override { return info_; }
  std::optional<std::string> unsupported(const RunRequest& r) const override {
    if (r.level < 1 || r.level > kMaxStencilDepth) return "depth must be 1.." + std::to_string(kMaxStencilDepth);
    return std::nullopt;
  }
  std::unique_ptr<Evaluation> prepare(const ControlMesh& mesh, const RunRequest& r) const override {
    using Threads = OsdStencilEvaluation::Threads;
    const Threads threads = r.backend != Backend::CpuMt      ? Threads::One
                            : r.parameters.integer("omp") ? Threads::OpenMp
                                                            : Threads::TbbRanges;
    return std::make_unique<OsdStencilEvaluation>(mesh, rule_, r.level, threads);
  }

 private:
  SubdivisionRule rule_;
  SchemeInfo info_;
};

}  // namespace

std::unique_ptr<Scheme> make_osd_stencil(SubdivisionRule rule) { return std::make_unique<OsdStencil>(rule); }

}  // namespace sdb
