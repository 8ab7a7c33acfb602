#include "registry.h"

#include "cpatch.h"
#include "geometry_image.h"
#include "peers.h"

namespace sdb {

const std::vector<std::unique_ptr<Scheme>>& all_schemes() {
  static const std::vector<std::unique_ptr<Scheme>> schemes = [] {
    std::vector<std::unique_ptr<Scheme>> list = make_peer_schemes();
    for (auto& s : make_cpatch_schemes()) list.push_back(std::move(s));
    list.push_back(make_geometry_image_scheme());
    list.push_back(make_geometry_image_scheme({.plan = gim::PassPlan::PerMask}));
    return list;
  }();
  return schemes;
}

const Scheme* find_scheme(std::string_view name) {
  for (const auto& s : all_schemes())
    if (s->info().name == name) return s.get();
  return nullptr;
}

}  // namespace sdb
