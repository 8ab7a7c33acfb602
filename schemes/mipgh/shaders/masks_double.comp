#version 450
// masks.glsl, summed in double.
#extension GL_GOOGLE_include_directive : require
#define SDB_DOUBLE 1
#include "masks.glsl"
