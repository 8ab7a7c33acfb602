#version 450
// One refinement level through the shape's pattern table, in slot order (tables.h): its face
// points (part kFaces), then its edge points (kEdges) and its vertex points (kVertices, a dispatch
// per kind of rule), which for Catmull-Clark read the face points just made.
#include "fragments.glsl"

void main() {
  if (!begin_invocation()) return;
  const uint h = header() + kHeaderPerLevel * (pc.level - 1u);
  const uint num_faces = table_word(h + 1u), faces = table_word(h + 2u), num_edges = table_word(h + 3u), edges = table_word(h + 4u);
  const uint num_vertices = table_word(h + 5u), vertices = table_word(h + 6u), ring = table_word(h + 7u);
  const bool catmark = (kFlags & kCatmark) != 0u;
  if (kPart == kFaces) {
    const uvec2 range = chunk_of(num_faces);
    for (uint i = range.x; i < range.y; ++i) {
      const uvec4 r = rule_words(faces + 4u * i);
      precise vec3 p = ((load(false, r.x) + load(false, r.z)) + (load(false, r.y) + load(false, r.w))) * 0.25;
      store(i, p);
    }
    return;
  }
  if (kPart == kEdges) {
    const uvec2 range = chunk_of(num_edges);
    for (uint j = range.x; j < range.y; ++j) {
      const uvec4 r = rule_words(edges + 8u * j), w = rule_words(edges + 8u * j + 4u);
      precise vec3 v = load(false, r.x) + load(false, r.y);
      const float wv = uintBitsToFloat(w.x), wf = uintBitsToFloat(w.y);
      precise vec3 p;
      if (wf == 0.0) {  // a crease: its f slots name no point (kernel.cpp)
        p = v * wv;
      } else {
        precise vec3 f = load(catmark, r.z) + load(catmark, r.w);
        p = v * wv + f * wf;
      }
      store(num_faces + j, p);
    }
    return;
  }
  // kVertices: the vertex rules of this dispatch's kind (kKind: their terms' formulas).
  const uint list = kind_list();
  const uvec2 range = chunk_of(kind_count());
  for (uint k = range.x; k < range.y; ++k) {
    const uint j = table_word(list + k);
    precise vec3 p = apply_vertex_rule(vertices + 12u * j, ring, catmark, kKind & 127u);
    store(num_faces + num_edges + j, p);
  }
}
