#include "harness/core/registry.h"

#include "harness/core/errors.h"

#include <algorithm>
#include <stdexcept>

namespace sdb {
namespace registry_detail {
namespace {

template <typename Factory>
struct Entry {
  std::string family;
  Factory make;
};

// Function-local statics: registrations from other translation units may run before any
// namespace-scope object of this one is constructed.
template <typename Factory>
std::vector<Entry<Factory>>& entries() {
  static std::vector<Entry<Factory>> list;
  return list;
}

template <typename Factory>
bool add(const char* family, Factory make) {
  entries<Factory>().push_back({family, make});
  return true;
}

template <typename Factory>
std::vector<Entry<Factory>> by_family() {
  std::vector<Entry<Factory>> sorted = entries<Factory>();
  std::stable_sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return a.family < b.family; });
  return sorted;
}

}  // namespace

bool add_schemes(const char* family, SchemeFactory make) { return add(family, make); }
bool add_paper_tables(const char* family, PaperFactory make) { return add(family, make); }
bool add_meshes(const char* family, MeshFactory make) { return add(family, make); }

}  // namespace registry_detail

const std::vector<std::unique_ptr<Scheme>>& all_schemes() {
  static const std::vector<std::unique_ptr<Scheme>> schemes = [] {
    std::vector<std::unique_ptr<Scheme>> list;
    for (const auto& e : registry_detail::by_family<registry_detail::SchemeFactory>())
      for (auto& s : e.make()) list.push_back(std::move(s));
    std::stable_sort(list.begin(), list.end(), [](const auto& a, const auto& b) { return a->info().role < b->info().role; });
    for (size_t i = 0; i < list.size(); ++i)
      for (size_t j = 0; j < i; ++j)
        if (list[i]->info().name == list[j]->info().name)
          throw std::logic_error("two schemes registered as '" + list[i]->info().name + "'");
    return list;
  }();
  return schemes;
}

const Scheme* find_scheme(std::string_view name) {
  for (const auto& s : all_schemes())
    if (s->info().name == name) return s.get();
  return nullptr;
}

ResolvedScheme resolve_scheme(const std::string& spelled) {
  const SchemeSpec spec = parse_scheme_spec(spelled);
  ResolvedScheme r;
  r.scheme = find_scheme(spec.name);
  if (!r.scheme) throw InputError(spec.name, "no such scheme (see `subdivbench list schemes`)");
  r.parameters = Parameters::resolve(r.scheme->info().parameters, spec);
  r.spec = spec.name + r.parameters.suffix();
  return r;
}

const std::vector<PaperTable>& paper_tables() {
  static const std::vector<PaperTable> tables = [] {
    std::vector<PaperTable> list;
    for (const auto& e : registry_detail::by_family<registry_detail::PaperFactory>())
      for (auto& t : e.make()) list.push_back(std::move(t));
    return list;
  }();
  return tables;
}

const std::vector<MeshProvider>& mesh_providers() {
  static const std::vector<MeshProvider> providers = [] {
    std::vector<MeshProvider> list;
    for (const auto& e : registry_detail::by_family<registry_detail::MeshFactory>()) list.push_back(e.make());
    return list;
  }();
  return providers;
}

}  // namespace sdb
