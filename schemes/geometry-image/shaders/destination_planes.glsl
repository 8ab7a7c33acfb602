// The destination image's planes at bindings GIM_DESTINATION, + 1, + 2 (define it first).
layout(std430, binding = GIM_DESTINATION) writeonly buffer DestinationX { float destination_x[]; };
layout(std430, binding = GIM_DESTINATION + 1) writeonly buffer DestinationY { float destination_y[]; };
layout(std430, binding = GIM_DESTINATION + 2) writeonly buffer DestinationZ { float destination_z[]; };

void store(uint i, vec3 v) {
  destination_x[i] = v.x;
  destination_y[i] = v.y;
  destination_z[i] = v.z;
}
