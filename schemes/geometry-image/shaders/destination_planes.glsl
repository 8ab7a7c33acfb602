// The destination image's planes at bindings GIM_DESTINATION, + 1, + 2 (define it first).
// Float texel views (r32f), written by imageStore: cheaper than storage-buffer stores on lavapipe.
layout(binding = GIM_DESTINATION, r32f) uniform restrict writeonly imageBuffer destination_x;
layout(binding = GIM_DESTINATION + 1, r32f) uniform restrict writeonly imageBuffer destination_y;
layout(binding = GIM_DESTINATION + 2, r32f) uniform restrict writeonly imageBuffer destination_z;

void store(uint i, vec3 v) {
  imageStore(destination_x, int(i), vec4(v.x));
  imageStore(destination_y, int(i), vec4(v.y));
  imageStore(destination_z, int(i), vec4(v.z));
}
