// The single list of schemes: paper methods and peers.
#pragma once

#include <memory>
#include <string_view>
#include <vector>

#include "scheme.h"

namespace sdb {

const std::vector<std::unique_ptr<Scheme>>& all_schemes();
const Scheme* find_scheme(std::string_view name);  // nullptr when unknown

}  // namespace sdb
