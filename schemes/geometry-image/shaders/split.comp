#version 450
// split.glsl, storing into a storage buffer (destination_planes.glsl).
#include "split.glsl"
