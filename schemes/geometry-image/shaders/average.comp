#version 450
// average.glsl, storing into a storage buffer (destination_planes.glsl).
#include "average.glsl"
