#include "harness/conformance/conformance.h"

SDB_CONFORMANCE_SUITE("halfedge-cc", "halfedge-loop");
