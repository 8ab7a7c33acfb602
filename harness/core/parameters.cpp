#include "harness/core/parameters.h"

#include <charconv>
#include <cmath>
#include <stdexcept>

#include "harness/core/errors.h"

namespace sdb {
namespace {

bool valid_key(std::string_view k) {
  if (k.empty() || k[0] < 'a' || k[0] > 'z') return false;
  for (char c : k)
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-')) return false;
  return true;
}

double parse_value(const ParameterSpec& p, const std::string& text, const std::string& where) {
  double v = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, v);
  if (ec != std::errc() || ptr != end || !std::isfinite(v))
    throw InputError(where, "parameter " + p.name + " needs a number, not '" + text + "'");
  if (p.integer && v != std::floor(v))
    throw InputError(where, "parameter " + p.name + " needs an integer, not '" + text + "'");
  if (v < p.min || v > p.max)
    throw InputError(where, "parameter " + p.name + " must lie in " + format_parameter(p.min, p.integer) + ".." +
                                format_parameter(p.max, p.integer) + ", not " + text);
  if (p.step > 0 && std::fmod(v - p.min, p.step) != 0)
    throw InputError(where, "parameter " + p.name + " takes " + format_parameter(p.min, p.integer) + ", " +
                                format_parameter(p.min + p.step, p.integer) + ", " +
                                format_parameter(p.min + 2 * p.step, p.integer) + " ... only, not " + text);
  return v;
}

}  // namespace

std::string format_parameter(double value, bool integer) {
  if (integer) return std::to_string(static_cast<long long>(value));
  char buf[32];
  const auto [ptr, ec] = std::to_chars(buf, buf + sizeof buf, value);
  return ec == std::errc() ? std::string(buf, ptr) : std::to_string(value);
}

SchemeSpec parse_scheme_spec(std::string_view text) {
  const std::string where(text);
  SchemeSpec spec;
  const size_t colon = text.find(':');
  spec.name = std::string(text.substr(0, colon));
  if (spec.name.empty()) throw InputError(where, "no scheme name before ':'");
  if (colon == std::string_view::npos) return spec;
  std::string_view rest = text.substr(colon + 1);
  while (true) {
    const size_t comma = rest.find(',');
    const std::string_view item = rest.substr(0, comma);
    const size_t eq = item.find('=');
    if (eq == std::string_view::npos || !valid_key(item.substr(0, eq)) || eq + 1 == item.size())
      throw InputError(where, "expected scheme:name=value[,name=value...], not '" + std::string(item) + "'");
    spec.assignments.emplace_back(std::string(item.substr(0, eq)), std::string(item.substr(eq + 1)));
    if (comma == std::string_view::npos) break;
    rest = rest.substr(comma + 1);
  }
  return spec;
}

Parameters Parameters::defaults(const std::vector<ParameterSpec>& declared) {
  Parameters p;
  for (const ParameterSpec& d : declared) p.values_[d.name] = d.default_value;
  return p;
}

Parameters Parameters::resolve(const std::vector<ParameterSpec>& declared, const SchemeSpec& spec) {
  Parameters p = defaults(declared);
  std::string where = spec.name;
  for (const auto& [k, v] : spec.assignments) where += (&k == &spec.assignments.front().first ? ":" : ",") + k + "=" + v;
  std::map<std::string, bool, std::less<>> assigned;
  for (const auto& [key, text] : spec.assignments) {
    const ParameterSpec* d = nullptr;
    for (const ParameterSpec& candidate : declared)
      if (candidate.name == key) d = &candidate;
    if (!d) {
      std::string known;
      for (const ParameterSpec& c : declared) known += (known.empty() ? "" : ", ") + c.name;
      throw InputError(where, spec.name + " has no parameter '" + key + "'" +
                                  (known.empty() ? " (it takes none)" : " (it takes " + known + ")"));
    }
    if (assigned[key]) throw InputError(where, "parameter " + key + " given twice");
    assigned[key] = true;
    p.values_[key] = parse_value(*d, text, where);
  }
  for (const ParameterSpec& d : declared)
    if (p.values_[d.name] != d.default_value)
      p.suffix_ += (p.suffix_.empty() ? ":" : ",") + d.name + "=" + format_parameter(p.values_[d.name], d.integer);
  return p;
}

double Parameters::value(std::string_view name) const {
  const auto it = values_.find(name);
  if (it == values_.end())
    throw std::logic_error("parameter '" + std::string(name) +
                           "' is not in this request: undeclared, or the request was not made by Parameters::resolve "
                           "or default_request");
  return it->second;
}

}  // namespace sdb
