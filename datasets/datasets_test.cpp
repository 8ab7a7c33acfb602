#include <gtest/gtest.h>

#include <cmath>

#include "datasets/generators.h"
#include "datasets/manifest.h"
#include "harness/core/errors.h"
#include "harness/mesh/facts.h"

using namespace sdb;


TEST(Generators, ClosedMeshesAreOrientedOutwardsWithTheRightGenus) {
  struct Case {
    ControlMesh mesh;
    int genus;
  };
  std::vector<Case> cases = {{gen::cube(), 0},         {gen::torus(8, 12), 1}, {gen::quad_sphere(3), 0},
                             {gen::icosphere(2), 0},   {gen::tetrahedron(), 0}, {gen::creased_cube(), 0},
                             {gen::random_quads(138, 0.38), 1}};
  for (int n = 3; n <= 8; ++n) cases.push_back({gen::pole(n), 0});
  for (const auto& c : cases) {
    const MeshFacts f = compute_facts(c.mesh);
    EXPECT_TRUE(f.closed) << c.mesh.name;
    EXPECT_TRUE(f.manifold()) << c.mesh.name;
    EXPECT_EQ(f.genus, c.genus) << c.mesh.name;
    EXPECT_EQ(f.unused_vertices, 0) << c.mesh.name;
    EXPECT_GT(signed_volume6(c.mesh), 0.0) << c.mesh.name << " is oriented inwards";
  }
}

TEST(Generators, TorusIsAllRegularAndPolesHaveTheirValence) {
  const MeshFacts t = compute_facts(gen::torus(6, 10));
  EXPECT_EQ(t.faces, 60);
  EXPECT_EQ(t.valences, (std::map<int, int>{{4, 60}}));
  EXPECT_EQ(t.extraordinary_quad_fraction, 0.0);
  for (int n = 3; n <= 8; ++n) {
    const MeshFacts p = compute_facts(gen::pole(n));
    EXPECT_TRUE(p.all_quads);
    EXPECT_GE(p.valences.at(n), 2) << "pole" << n;
  }
  const MeshFacts ico = compute_facts(gen::icosphere(1));
  EXPECT_EQ(ico.faces, 80);
  EXPECT_TRUE(ico.all_triangles);
}

TEST(Generators, OpenPatchHasOneBoundaryLoop) {
  const MeshFacts f = compute_facts(gen::open_patch(4, 3));
  EXPECT_FALSE(f.closed);
  EXPECT_EQ(f.boundary_edges, 2 * (4 + 3));
  EXPECT_EQ(f.boundary_loops, 1);
  EXPECT_EQ(f.genus, 0);
}

// The papers' models, stood in for: same quad count, extraordinary share within one quad.
TEST(Generators, RandomQuadsHitThePapersCountsAndShares) {
  struct Target {
    int quads;
    double share;
  };
  for (const Target t : {Target{138, 0.38}, Target{600, 1.0}, Target{1292, 0.59}}) {
    const ControlMesh m = gen::random_quads(t.quads, t.share, 1);
    const MeshFacts f = compute_facts(m);
    EXPECT_EQ(f.faces, t.quads);
    EXPECT_TRUE(f.all_quads);
    EXPECT_TRUE(f.closed && f.manifold());
    EXPECT_NEAR(f.extraordinary_quad_fraction, t.share, 1.5 / t.quads) << m.name;
  }
  EXPECT_THROW(gen::random_quads(13, 0.5), InputError);  // prime: no torus grid
}

TEST(Manifest, BuiltinsAndParametrisedNamesLoad) {
  for (const auto& e : list_meshes())
    if (e.kind == "builtin") {
      EXPECT_GT(num_faces(load_mesh(e.name)), 0) << e.name;
    }
  EXPECT_EQ(num_faces(load_mesh("torus-5x7")), 35);
  EXPECT_EQ(num_faces(load_mesh("quadsphere-2")), 24);
  EXPECT_EQ(num_faces(load_mesh("random-100-50")), 100);
  EXPECT_THROW(load_mesh("no-such-mesh"), InputError);
}

// tests/fuzz: random-4000000-100 ran for hours (the rotations are quadratic in the quads).
TEST(Generators, RandomQuadsAreCappedWhereTheirTimeIsBounded) {
  EXPECT_EQ(num_faces(load_mesh("random-1300-50")), 1300);
  try {
    load_mesh("random-1302-100");
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("random-1302-100: 1302 quads: at most 1300", 0), 0u) << e.what();
  }
}

// A 60,000-character name overflowed the stack in libstdc++'s regex (found with tests/fuzz's
// mesh-name target): a name that long is no generator name, and load_mesh says no such mesh.
TEST(Manifest, LongNamesAreNoGeneratorNames) {
  const std::string name = "torus-" + std::string(60000, '1') + "x3";
  EXPECT_FALSE(generated_mesh(name).has_value());
  EXPECT_THROW(load_mesh(name), InputError);
  EXPECT_EQ(num_faces(*generated_mesh("torus-3x4")), 12);
  EXPECT_FALSE(generated_mesh("crane/spot_control").has_value());
}

// Every OBJ, OFF and PLY file of the shared corpus loads (non-manifold ones are reported, not refused).
TEST(Manifest, EveryCorpusFileLoads) {
  if (!corpus_dir()) GTEST_SKIP() << "shared corpus not found beside the checkout";
  int loaded = 0;
  for (const auto& e : list_meshes()) {
    if (e.kind != "corpus") continue;
    EXPECT_NO_THROW({
      const ControlMesh m = load_mesh(e.name);
      EXPECT_GT(num_faces(m), 0);
      ++loaded;
    }) << e.name;
  }
  EXPECT_GE(loaded, 90);
}
