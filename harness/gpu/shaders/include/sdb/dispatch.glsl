// SDB_LINEAR_INVOCATION(): index of this invocation in a dispatch sized by sdb::gpu::groups_for()
// (work groups x first, then y, then z). Compare it with the element count: the last row of
// groups over-covers.
//
//   #extension GL_GOOGLE_include_directive : require
//   #include "sdb/dispatch.glsl"
//   layout(local_size_x = 64) in;
//   ... uint i = SDB_LINEAR_INVOCATION(); if (i >= count) return;
//
// A macro, not a function: gl_WorkGroupSize is (1, 1, 1) in code that precedes the
// layout(local_size_x = ...) declaration (glslang does not complain), so it must be read where
// it is used.
#define SDB_LINEAR_INVOCATION()                                                                          \
  (((gl_WorkGroupID.z * gl_NumWorkGroups.y + gl_WorkGroupID.y) * gl_NumWorkGroups.x + gl_WorkGroupID.x) * \
       (gl_WorkGroupSize.x * gl_WorkGroupSize.y * gl_WorkGroupSize.z) +                                  \
   gl_LocalInvocationIndex)
