// as_words(v): a 16-byte element (four floats) as two 64-bit words, for a storage buffer of
// u64vec2. lavapipe stores to memory lane by lane and component by component, so two 64-bit
// components cost about a third of an rgba32f imageStore and under half of a vec4 store
// (harness/gpu/README.md, "Memory access on lavapipe"). The bits go through unchanged
// (packUint2x32: the first float in the low half, which is first in memory). Needs shaderInt64.
//
//   #extension GL_GOOGLE_include_directive : require
//   #include "sdb/words.glsl"
#extension GL_ARB_gpu_shader_int64 : require

u64vec2 as_words(vec4 v) {
  const uvec4 b = floatBitsToUint(v);
  return u64vec2(packUint2x32(b.xy), packUint2x32(b.zw));
}
