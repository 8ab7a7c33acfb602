#include "harness/conformance/conformance.h"

SDB_CONFORMANCE_SUITE("mipgh-cc", "mipgh-loop", "mipgh-quadtri");
