#include "harness/conformance/conformance.h"

// The analytic image is this scheme's own mesh (registered in scheme.cpp): the g0 it subdivides as is.
SDB_CONFORMANCE_SUITE_WITH_MESHES(std::vector<std::string>{"gim-sphere-31"}, "geometry-image", "geometry-image-permask");
