// Procedural meshes, so the harness runs on a machine without the shared corpus.
#pragma once

#include <cstdint>

#include "harness/core/control_mesh.h"

namespace sdb::gen {

ControlMesh cube();                                    // 8 vertices, 6 quads, valence 3 corners
ControlMesh torus(int m, int n, float major = 1.0f, float minor = 0.4f);  // m x n quads, all valence 4
ControlMesh quad_sphere(int k);                        // cube-sphere, 6 k^2 quads
ControlMesh pole(int n, int bands = 4);                // closed, two valence-n poles
ControlMesh icosphere(int level);                      // 20 * 4^level triangles
ControlMesh tetrahedron();
ControlMesh creased_cube(float sharpness = 2.0f);      // cube with every edge creased
ControlMesh open_patch(int m, int n);                  // m x n quads with boundary
// A closed quad mesh with `quads` quads whose share of extraordinary quads is close to
// `extraordinary_share`: a torus grid whose connectivity is changed by random quad edge rotations.
ControlMesh random_quads(int quads, double extraordinary_share, uint64_t seed = 1);
// Each quad of a mesh split into two triangles, along the diagonal from its second corner in every
// third face and its first in the others: a random quad mesh gives triangle valences of 3 to 11.
ControlMesh split_quads(const ControlMesh& mesh);
// `copies` copies of a mesh side by side in a row of a grid (the c-patch paper's frog party).
ControlMesh party(const ControlMesh& mesh, int copies);

}  // namespace sdb::gen
