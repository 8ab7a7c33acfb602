// The destination image at binding GIM_DESTINATION (define it first): one 16-byte element per
// sample, (x, y, z, 0). A storage buffer of vec4 where the image fits one storage binding; an
// rgba32f storage texel view where it does not (GIM_TEXEL_DESTINATION, the *_texels.comp variants:
// a binding covers 128 MiB on lavapipe, a texel view 2 GiB).
#ifdef GIM_TEXEL_DESTINATION
layout(binding = GIM_DESTINATION, rgba32f) uniform restrict writeonly imageBuffer destination;

void store(uint i, vec3 v) { imageStore(destination, int(i), vec4(v, 0.0)); }
#else
layout(std430, binding = GIM_DESTINATION) restrict writeonly buffer Destination { vec4 destination[]; };

void store(uint i, vec3 v) { destination[i] = vec4(v, 0.0); }
#endif
