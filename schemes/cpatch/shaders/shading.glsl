// What every c-patch render stage hands the rasterizer: the clip-space position and the normal in
// view space (seven output components per vertex, which bounds the 1-pass geometry shader's N).
// Needs buffers.glsl with BINDING_CAMERA.
layout(location = 0) out vec3 view_normal;

vec4 clip_position(vec3 position) { return camera.mvp * vec4(position, 1.0); }

vec3 to_view(vec3 normal) {
  return vec3(dot(camera.view_rows[0].xyz, normal), dot(camera.view_rows[1].xyz, normal),
              dot(camera.view_rows[2].xyz, normal));
}

// Blue (0) - white (1/2) - red (1) diverging scale, clamped.
vec3 heat_colour(float t) {
  t = clamp(t, 0.0, 1.0);
  const vec3 blue = vec3(0.23, 0.30, 0.75), white = vec3(0.87, 0.87, 0.87), red = vec3(0.71, 0.02, 0.15);
  return t < 0.5 ? mix(blue, white, 2.0 * t) : mix(white, red, 2.0 * t - 1.0);
}
