// The source image's planes at bindings 0, 1, 2 and src(i): the sample at padded index i.
layout(std430, binding = 0) readonly buffer SourceX { float source_x[]; };
layout(std430, binding = 1) readonly buffer SourceY { float source_y[]; };
layout(std430, binding = 2) readonly buffer SourceZ { float source_z[]; };

vec3 src(uint i) { return vec3(source_x[i], source_y[i], source_z[i]); }
