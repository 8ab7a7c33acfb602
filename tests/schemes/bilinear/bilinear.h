// bilinear-limit: a test-only scheme (SchemeRole::Test), compiled into the tests alone. It joins
// the limit surface's points at the corners of every quad bilinearly: a scheme small enough to
// read in a minute that exercises the whole plug-in seam (self-registration, the conformance
// suite, the gate's pairing with its peer). README.md.
#pragma once

#include <memory>

#include "harness/core/scheme.h"

namespace sdb {

std::unique_ptr<Scheme> make_bilinear_limit_scheme();

}  // namespace sdb
