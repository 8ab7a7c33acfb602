#version 450
// masks.glsl, summed in float (a device without shaderFloat64).
#extension GL_GOOGLE_include_directive : require
#include "masks.glsl"
