// The source image's planes at bindings 0, 1, 2 and src(i): the sample at padded index i. Float
// texel views of the plane buffers: a texel fetch is one vector gather on lavapipe, a
// storage-buffer load a branch per lane (harness/gpu/README.md, "Memory access on lavapipe").
layout(binding = 0) uniform samplerBuffer source_x;
layout(binding = 1) uniform samplerBuffer source_y;
layout(binding = 2) uniform samplerBuffer source_z;

vec3 src(uint i) { return vec3(texelFetch(source_x, int(i)).x, texelFetch(source_y, int(i)).x, texelFetch(source_z, int(i)).x); }
