// The source image at binding 0 and src(i): the sample at padded index i, one vec4 texel (xyz).
// A texel fetch is one vector gather on lavapipe, a storage-buffer load a branch per lane and
// float (harness/gpu/README.md, "Memory access on lavapipe").
layout(binding = 0) uniform samplerBuffer source;

vec3 src(uint i) { return texelFetch(source, int(i)).xyz; }
