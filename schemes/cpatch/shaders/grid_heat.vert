#version 450
#extension GL_GOOGLE_include_directive : require
#define HEAT_MAP 1
#include "grid_body.glsl"
