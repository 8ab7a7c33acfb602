// The CPU evaluation of bilinear-limit (cpu and cpu-mt).
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "harness/core/scheme.h"
#include "harness/reference/shared_layout.h"

namespace sdb::bilinear {

class BilinearEvaluation final : public Evaluation {
 public:
  // `quads`: an all-quad mesh. `repeat`: how many times execute() does its work.
  BilinearEvaluation(const ControlMesh& quads, int rate, bool multithreaded, int repeat);
  void execute() override;
  const Tessellation& result() override { return out_; }
  size_t bytes_out() const override { return out_.positions.size() * 2 * sizeof(Point3); }

 private:
  void evaluate_face(size_t f);

  std::vector<std::array<Point3, 4>> corner_positions_, corner_normals_;  // per quad, (0,0) (1,0) (1,1) (0,1)
  std::vector<std::vector<SharedLayout::Owned>> owned_;
  bool multithreaded_;
  int repeat_;
  Tessellation out_;
};

}  // namespace sdb::bilinear
