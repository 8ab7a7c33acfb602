#include "harness/conformance/conformance.h"

SDB_CONFORMANCE_SUITE("edgefriend-cc");
