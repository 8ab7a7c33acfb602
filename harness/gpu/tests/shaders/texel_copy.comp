#version 450
// out[i] = (in[i].x + in[i].y) * in[i].z - in[i].w: vec4 texels read through a uniform texel
// buffer, float texels written through a storage texel buffer (r32f).

layout(local_size_x = 64) in;
layout(binding = 0) uniform samplerBuffer in_texels;
layout(binding = 1, r32f) uniform restrict writeonly imageBuffer out_texels;
layout(push_constant) uniform Push { uint count; } pc;

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  const vec4 v = texelFetch(in_texels, int(i));
  precise float r = (v.x + v.y) * v.z - v.w;
  imageStore(out_texels, int(i), vec4(r));
}
