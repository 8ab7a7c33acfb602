#version 450
#extension GL_GOOGLE_include_directive : require
#define HEAT_MAP 0
#include "grid_body.glsl"
