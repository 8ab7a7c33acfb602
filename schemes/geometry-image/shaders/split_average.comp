#version 450
// split_average.glsl, storing into a storage buffer (destination_planes.glsl).
#include "split_average.glsl"
