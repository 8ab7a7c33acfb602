#version 450
#extension GL_GOOGLE_include_directive : require
#define STORE_OUTPUT 0
#include "patch_body.glsl"
