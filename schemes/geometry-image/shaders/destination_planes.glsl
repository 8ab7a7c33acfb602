// The destination image at binding GIM_DESTINATION (define it first).
// An rgba32f texel view written by imageStore: one store per sample (w unused, 0).
layout(binding = GIM_DESTINATION, rgba32f) uniform restrict writeonly imageBuffer destination;

void store(uint i, vec3 v) { imageStore(destination, int(i), vec4(v, 0.0)); }
