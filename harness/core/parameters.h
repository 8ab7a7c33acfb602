// Typed scheme parameters: what a scheme lets a user set besides backend and level (the
// geometry-image fit size, say), declared in its SchemeInfo, spelled on the command line as
// `--scheme geometry-image:fit=129`, handed to prepare() in the RunRequest and recorded in the row.
#pragma once

#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace sdb {

struct ParameterSpec {
  std::string name;  // [a-z][a-z0-9-]*
  std::string description;
  bool integer = true;
  double default_value = 0;
  double min = 0, max = 0;  // inclusive
  double step = 0;          // > 0: the valid values are min, min + step, min + 2 step, ...
};

// A scheme as the command line names it: "geometry-image" or "geometry-image:fit=129,x=2".
struct SchemeSpec {
  std::string name;
  std::vector<std::pair<std::string, std::string>> assignments;  // as written, in order
};

// Throws InputError naming `text` when it is not `name[:key=value[,key=value]...]`.
SchemeSpec parse_scheme_spec(std::string_view text);

// The value of every parameter a scheme declares: from its default, or as assigned.
class Parameters {
 public:
  Parameters() = default;
  // InputError naming the spec for an unknown name, a repeated one, a malformed number, or a
  // value outside the declared range or step.
  static Parameters resolve(const std::vector<ParameterSpec>& declared, const SchemeSpec& spec);
  // Every parameter at its default.
  static Parameters defaults(const std::vector<ParameterSpec>& declared);

  // std::logic_error for a name the scheme did not declare: a bug in the scheme, not input.
  double value(std::string_view name) const;
  int integer(std::string_view name) const { return static_cast<int>(value(name)); }
  const std::map<std::string, double, std::less<>>& values() const { return values_; }
  // ":fit=129,x=2": the values that differ from their default, in declared order; "" when all are
  // defaults.
  // The scheme's name plus this suffix names the variant in run names and results rows.
  const std::string& suffix() const { return suffix_; }

 private:
  std::map<std::string, double, std::less<>> values_;
  std::string suffix_;
};

// A value as spelled in run names and messages: integers without a decimal point.
std::string format_parameter(double value, bool integer);

}  // namespace sdb
