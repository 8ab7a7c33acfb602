#include "harness/conformance/conformance.h"

SDB_CONFORMANCE_SUITE("osd-uniform", "osd-uniform-loop", "osd-bfr", "embree-subdiv");
