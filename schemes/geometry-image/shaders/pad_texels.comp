#version 450
// pad.glsl, storing through a texel view: for images past one storage binding
// (destination_planes.glsl).
#define GIM_TEXEL_DESTINATION 1
#include "pad.glsl"
