#version 450
// pad.glsl, storing into a storage buffer (destination_planes.glsl).
#include "pad.glsl"
