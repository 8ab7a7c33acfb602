// The cpu and cpu-mt evaluations' frame, as both peers run it: run() on this thread, or (cpu-mt)
// on TBB's, in an arena of `threads` where the request names a count (0: TBB's default).
#pragma once

#include <tbb/task_arena.h>

#include <memory>

#include "harness/core/scheme.h"

namespace sdb::refined {

class CpuFrame : public Evaluation {
 public:
  void execute() final {
    if (arena_) arena_->execute([&] { run(); });
    else run();
  }
  const Tessellation& result() final { return output(); }
  size_t bytes_out() const final { return output().positions.size() * 2 * sizeof(Point3); }

 protected:
  CpuFrame(bool multithreaded, int threads) : multithreaded_(multithreaded) {
    if (multithreaded && threads > 0) arena_ = std::make_unique<tbb::task_arena>(threads);
  }
  virtual void run() = 0;
  virtual const Tessellation& output() const = 0;  // positions and normals written by run()

  const bool multithreaded_;

 private:
  std::unique_ptr<tbb::task_arena> arena_;
};

}  // namespace sdb::refined
