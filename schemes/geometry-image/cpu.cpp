// The cpu and cpu-mt evaluations: the Subdivider's passes on one thread or on TBB's.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "schemes/geometry-image/backends.h"
#include "schemes/geometry-image/tessellation_grid.h"

namespace sdb::gim {

namespace {

// cpu-mt: rows in blocks of a few, each block computed exactly as the serial pass computes it.
class TbbRows final : public RowExecutor {
 public:
  explicit TbbRows(int threads) : arena_(threads > 0 ? threads : tbb::task_arena::automatic) {}
  void for_rows(int rows, RowBody body) const override {
    arena_.execute([&] {
      tbb::parallel_for(tbb::blocked_range<int>(0, rows, 4), [&](const tbb::blocked_range<int>& r) {
        body({r.begin(), r.end()});
      });
    });
  }

 private:
  mutable tbb::task_arena arena_;
};

class CpuEvaluation final : public Evaluation {
 public:
  explicit CpuEvaluation(const EvaluationInput& in) : g0_(in.g0), subdivider_(in.base_size, in.request.level, in.plan) {
    if (in.request.backend == Backend::CpuMt)
      rows_ = std::make_unique<TbbRows>(in.request.threads);
    else
      rows_ = std::make_unique<SerialRows>();
    out_ = grid_tessellation(in.base_size, in.request.level, subdivider_.size(in.request.level), g0_);
  }

  void execute() override {
    subdivider_.run(g0_->positions.data(), out_.positions.data(), out_.normals.data(), *rows_);
  }
  const Tessellation& result() override { return out_; }
  size_t bytes_out() const override { return out_.positions.size() * 2 * sizeof(Point3); }

 private:
  std::shared_ptr<const ControlMesh> g0_;
  Subdivider subdivider_;
  std::unique_ptr<RowExecutor> rows_;
  Tessellation out_;
};

}  // namespace

std::unique_ptr<Evaluation> make_cpu_evaluation(const EvaluationInput& input) {
  return std::make_unique<CpuEvaluation>(input);
}

}  // namespace sdb::gim
