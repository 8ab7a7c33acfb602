#include "harness/conformance/conformance.h"

SDB_CONFORMANCE_SUITE("fragments-cc", "fragments-loop");
