// One run as the command line, Google Benchmark and the gate name it: scheme/backend/mesh/level,
// the scheme as spelled with its parameters ("geometry-image:fit=129/cpu/crane/spot_control/3").
// The one place that name is built and read.
#pragma once

#include <string>
#include <string_view>

#include "harness/core/backend.h"

namespace sdb {

struct RunSpec {
  std::string scheme;  // "geometry-image" or "geometry-image:fit=129" (harness/core/parameters.h)
  std::string mesh;
  Backend backend = Backend::Cpu;
  int level = 0;
  std::string name() const;
};

std::string run_name(std::string_view scheme, Backend backend, std::string_view mesh, int level);

// InputError naming `name` unless it is scheme/backend/mesh/level with a known backend and an
// integer level (the mesh may hold slashes: "crane/spot_control").
RunSpec parse_run_name(const std::string& name);

}  // namespace sdb
