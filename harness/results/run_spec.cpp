#include "harness/results/run_spec.h"

#include <charconv>

#include "harness/core/errors.h"

namespace sdb {

std::string run_name(std::string_view scheme, Backend backend, std::string_view mesh, int level) {
  std::string s(scheme);
  s += "/";
  s += to_string(backend);
  s += "/";
  s += mesh;
  s += "/" + std::to_string(level);
  return s;
}

std::string RunSpec::name() const { return run_name(scheme, backend, mesh, level); }

RunSpec parse_run_name(const std::string& name) {
  const size_t first = name.find('/'), second = first == std::string::npos ? first : name.find('/', first + 1);
  const size_t last = name.rfind('/');
  if (first == 0 || second == std::string::npos || last <= second + 1 || last + 1 == name.size())
    throw InputError(name, "expected scheme/backend/mesh/level");
  RunSpec spec;
  spec.scheme = name.substr(0, first);
  const auto backend = parse_backend(std::string_view(name).substr(first + 1, second - first - 1));
  if (!backend) throw InputError(name, "no such backend '" + name.substr(first + 1, second - first - 1) + "' (" + backend_names() + ")");
  spec.backend = *backend;
  spec.mesh = name.substr(second + 1, last - second - 1);
  const char* begin = name.data() + last + 1;
  const char* end = name.data() + name.size();
  const auto [ptr, ec] = std::from_chars(begin, end, spec.level);
  if (ec != std::errc() || ptr != end) throw InputError(name, "the level must be an integer, not '" + name.substr(last + 1) + "'");
  return spec;
}

}  // namespace sdb
