#include "harness/conformance/conformance.h"

SDB_CONFORMANCE_SUITE("cpatch-2pass", "cpatch-1pass", "cpatch-tess");
