// Hand-made results rows with given repetition times, for the tests of what reads times (the gate,
// the history): nothing is measured.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "harness/results/results.h"

namespace sdb::test {

// An ok row of `scheme` on `backend` on the mesh "cube" at `level` (tessellation 8) whose
// repetitions took `samples` ms, judged against `peer` on `peer_backend` where given.
inline RunRow timed_row(const std::string& scheme, Backend backend, std::vector<double> samples, const std::string& peer = "",
                        std::optional<Backend> peer_backend = std::nullopt, int level = 9) {
  RunRow r;
  r.scheme = r.spec = scheme;
  r.backend = backend;
  r.mesh = "cube";
  r.level = level;
  r.tessellation = 8;
  r.peer = peer;
  r.peer_backend = peer_backend;
  r.time_ms = TimeStats{1, 1, 1, int(samples.size()), samples};
  return r;
}

}  // namespace sdb::test
