// Factories of the individual peers (see peers.h for what each is).
#pragma once

#include <memory>

#include "scheme.h"

namespace sdb {

std::unique_ptr<Scheme> make_osd_uniform(SubdivisionRule rule);
std::unique_ptr<Scheme> make_osd_bfr();
std::unique_ptr<Scheme> make_embree_subdiv();

}  // namespace sdb
