// Unit tests of the c-patch conversion (Tables 1, 2, equations (3)-(5)) and of the patch
// evaluation, on small meshes. Surface-level properties (limit, Lemma 1, weld) are in
// cpatch_surface_test.cpp.
#include "schemes/cpatch/cpatch.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "datasets/manifest.h"
#include "harness/mesh/acceptance.h"
#include "schemes/cpatch/conversion.h"
#include "schemes/cpatch/cpu.h"
#include "schemes/cpatch/evaluation.h"
#include "schemes/cpatch/topology.h"

using namespace sdb;
using namespace sdb::cpatch;

namespace {

ControlMesh accepted(const std::string& name) { return accept_mesh(load_mesh(name), cpatch_2pass_info()); }

double distance(const std::array<double, 3>& a, const Vec3d& b) {
  return std::sqrt((a[0] - b.x) * (a[0] - b.x) + (a[1] - b.y) * (a[1] - b.y) + (a[2] - b.z) * (a[2] - b.z));
}
double distance(Vec3f a, Vec3f b) { return std::sqrt(double(dot(a - b, a - b))); }
double norm(const std::array<double, 3>& a) { return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

Vec3d cubic_at(const Vec3d p[4], double t) {
  const double s = 1.0 - t, w[4] = {s * s * s, 3 * s * s * t, 3 * s * t * t, t * t * t};
  Vec3d out;
  for (int k = 0; k < 4; ++k) out = out + w[k] * p[k];
  return out;
}

// A record's corner entry (v, t_0, t_1) as an absolute point.
Vec3d corner_point(const Vec3f* record, int corner, RecordEntry e) {
  return to_double(record[record_index(corner, kP)]) + to_double(record[record_index(corner, e)]);
}

double bbox_diagonal(const ControlMesh& m) { return bounds_of(m.positions).diagonal(); }

}  // namespace

TEST(Topology, NeighbourhoodsListQuadsCounterClockwiseAroundEachVertex) {
  for (const char* name : {"torus-8x12", "pole5", "frog-standin"}) {
    const ControlMesh m = accepted(name);
    const CpatchTopology t = build_topology(m);
    for (int q = 0; q < t.num_quads; ++q)
      for (int i = 0; i < 4; ++i) {
        const QuadCorner& c = t.corners[4 * q + i];
        const int* qv = &t.quad_vertices[4 * q];
        EXPECT_EQ(c.vertex, qv[i]);
        // Sector j of the corner's vertex is this quad: p_{2j} = q_{i+1}, p_{2j+1} = q_{i+2}, and
        // the next sector's direct neighbour p_{2j+2} is q_{i-1}.
        EXPECT_EQ(t.ring[2 * c.sector_slot], qv[(i + 1) % 4]) << name;
        EXPECT_EQ(t.ring[2 * c.sector_slot + 1], qv[(i + 2) % 4]) << name;
        EXPECT_EQ(t.ring[2 * c.prev_edge_slot], qv[(i + 3) % 4]) << name;
      }
  }
}

TEST(Topology, AllOrdinaryMeshHasNoCpatches) {
  const CpatchTopology t = build_topology(accepted("torus-8x12"));
  EXPECT_EQ(t.num_quads, 96);
  EXPECT_TRUE(t.extraordinary_quads.empty());
  EXPECT_EQ(t.ordinary_quads.size(), 96u);
  const CpatchTopology frog = build_topology(accepted("frog-standin"));
  EXPECT_GT(frog.extraordinary_quads.size(), 0u);
  EXPECT_EQ(frog.extraordinary_quads.size() + frog.ordinary_quads.size(), size_t(frog.num_quads));
}

TEST(Table1, SubdominantEigenvalueIsOneHalfForValenceFour) {
  EXPECT_DOUBLE_EQ(subdominant_eigenvalue(4), 0.5);
  // Catmull-Clark's lambda = (5 + c + cos(pi/n) sqrt(2 (9 + c))) / 16 in its usual form.
  for (int n = 3; n <= 12; ++n) {
    const double c = std::cos(2 * M_PI / n);
    EXPECT_NEAR(subdominant_eigenvalue(n), (5 + c + std::cos(M_PI / n) * std::sqrt(2 * (9 + c))) / 16, 1e-15) << n;
  }
}

// Equation (1): for n = 4, the projection of Table 1 returns the edge points unchanged. The
// converter short-cuts n = 4 on the strength of this; here the projection itself is checked.
TEST(Table1, ProjectionLeavesEdgePointsOfValenceFourUnchanged) {
  const ControlMesh m = accepted("frog-standin");
  CpatchCpuEvaluation eval(m, 2, false);
  eval.execute();
  const CpatchTopology& t = eval.topology();
  const VertexPoints& p = eval.vertex_points();
  const ValenceConstants& k = t.valence_constants[4];
  const double scale = bbox_diagonal(m);
  int checked = 0;
  for (int v = 0; v < t.num_vertices; ++v) {
    if (t.valence[v] != 4) continue;
    Vec3f projected[4];
    const int s = t.first_slot[v];
    project_tangents(p.limit[v], &p.edge[s], 4, k, &t.trig_cos[k.trig_offset], &t.trig_sin[k.trig_offset], projected);
    for (int j = 0; j < 4; ++j) EXPECT_LE(distance(projected[j], p.edge[s + j]), 1e-6 * scale);
    ++checked;
  }
  EXPECT_GT(checked, 100);
}

// All t_j of a vertex lie in one plane through v (the tangent plane), also for n != 4.
TEST(Table1, TangentPointsAreCoplanarWithTheLimitPoint) {
  const ControlMesh m = accepted("frog-standin");
  CpatchCpuEvaluation eval(m, 2, false);
  eval.execute();
  const CpatchTopology& t = eval.topology();
  const VertexPoints& p = eval.vertex_points();
  const double tolerance = 1e-6 * bbox_diagonal(m);  // float rounding of points of that magnitude
  for (int v = 0; v < t.num_vertices; ++v) {
    const int s = t.first_slot[v], n = t.valence[v];
    const Vec3d center = to_double(p.limit[v]);
    const Vec3d normal = cross(to_double(p.tangent[s]) - center, to_double(p.tangent[s + 1]) - center);
    const Vec3d unit = (1.0 / std::sqrt(dot(normal, normal))) * normal;
    for (int j = 2; j < n; ++j)
      EXPECT_LE(std::abs(dot(to_double(p.tangent[s + j]) - center, unit)), tolerance)
          << "vertex " << v << " valence " << n;
  }
}

// Equation (5) with the average constraint: the corrected Table 2 b112 satisfies
// b112^i - b112^{i+1} = (b211^i - b121^{i+1} - q) / 2 for all four rows and averages to g(1/2, 1/2).
TEST(Table2, B112SolvesEquationFiveWithTheAverageConstraint) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> coord(-1.0f, 1.0f);
  auto random_point = [&] { return Vec3f{coord(rng), coord(rng), coord(rng)}; };
  const int valences[4] = {3, 5, 4, 6};
  CpatchCornerInput in[4];
  CpatchCornerWeights w[4];
  for (int i = 0; i < 4; ++i) {
    in[i] = {random_point(), random_point(), random_point(), random_point(), random_point(), random_point()};
    const double ci = std::cos(2 * M_PI / valences[i]), cn = std::cos(2 * M_PI / valences[(i + 1) % 4]);
    const double si = std::sin(2 * M_PI / valences[i]), sn = std::sin(2 * M_PI / valences[(i + 1) % 4]);
    w[i] = {float((1 + ci) / 4), float((1 - cn) / 8), float((1 + cn) / 4), float((1 - ci) / 8),
            float(3 / (4 * (si + sn)))};
  }
  const CpatchInterior b = cpatch_interior(in, w);
  Vec3d q{};
  for (int i = 0; i < 4; ++i) q = q + 0.25 * (to_double(b.b211[i]) - to_double(b.b121[i]));
  for (int i = 0; i < 4; ++i) {
    const int i1 = (i + 1) % 4;
    const Vec3d lhs = to_double(b.b112[i]) - to_double(b.b112[i1]);
    const Vec3d rhs = 0.5 * (to_double(b.b211[i]) - to_double(b.b121[i1]) - q);
    EXPECT_NEAR(lhs.x, rhs.x, 1e-5);
    EXPECT_NEAR(lhs.y, rhs.y, 1e-5);
    EXPECT_NEAR(lhs.z, rhs.z, 1e-5);
  }
  Vec3d g{}, mean{};
  for (int i = 0; i < 4; ++i) {
    g = g + (1.0 / 64) *
                (to_double(in[i].v) + 3.0 * (to_double(in[i].e0) + to_double(in[i].e1)) + 9.0 * to_double(in[i].f));
    mean = mean + 0.25 * to_double(b.b112[i]);
  }
  EXPECT_NEAR(mean.x, g.x, 1e-5);
  EXPECT_NEAR(mean.y, g.y, 1e-5);
  EXPECT_NEAR(mean.z, g.z, 1e-5);
}

// The c-patch's outer boundary is the cubic (v^i, t_0^i, t_1^{i+1}, v^{i+1}) that a bicubic
// neighbour has there: evaluate the quartic pieces along each side against that cubic.
TEST(Cpatch, ReproducesTheBicubicBoundaryCurves) {
  const ControlMesh m = accepted("frog-standin");
  CpatchCpuEvaluation eval(m, 2, false);
  eval.execute();
  const CpatchTopology& t = eval.topology();
  ASSERT_FALSE(t.extraordinary_quads.empty());
  for (int q : t.extraordinary_quads) {
    const PatchRecord record = eval.record(q);
    const Vec3f* r = record.data();
    for (int side = 0; side < 4; ++side) {
      const int a = side, b = (side + 1) % 4;
      const Vec3d cubic[4] = {corner_point(r, a, kV), corner_point(r, a, kT0), corner_point(r, b, kT1),
                              corner_point(r, b, kV)};
      for (double s : {0.0, 0.1, 0.25, 0.5, 0.7, 1.0}) {
        const double uv[4][2] = {{s, 0}, {1, s}, {1 - s, 1}, {0, 1 - s}};
        const PatchPoint p = cpatch_at(r, uv[side][0], uv[side][1]);
        EXPECT_LE(distance(p.position, cubic_at(cubic, s)), 1e-6 * norm(p.position) + 1e-9) << "quad " << q;
      }
    }
  }
}

// Equation (3) makes adjacent pieces of one c-patch join C1: value and both derivatives agree on
// the diagonals when approached from either piece.
TEST(Cpatch, PiecesJoinWithContinuousDerivatives) {
  const ControlMesh m = accepted("pole5");
  CpatchCpuEvaluation eval(m, 2, false);
  eval.execute();
  const double eps = 1e-7;
  for (int q : eval.topology().extraordinary_quads) {
    const PatchRecord record = eval.record(q);
    const Vec3f* r = record.data();
    for (double s : {0.05, 0.2, 0.35, 0.65, 0.8, 0.95}) {
      // Points on the diagonal u = v and on u = 1 - v, approached from both sides.
      const double points[2][2][2] = {{{s + eps, s - eps}, {s - eps, s + eps}},
                                      {{s + eps, 1 - s + eps}, {s - eps, 1 - s - eps}}};
      for (const auto& pair : points) {
        const PatchPoint a = cpatch_at(r, pair[0][0], pair[0][1]), b = cpatch_at(r, pair[1][0], pair[1][1]);
        const double scale = norm(a.du) + norm(a.dv);
        for (int k = 0; k < 3; ++k) {
          EXPECT_NEAR(a.du[k], b.du[k], 1e-5 * scale) << "quad " << q;
          EXPECT_NEAR(a.dv[k], b.dv[k], 1e-5 * scale) << "quad " << q;
        }
      }
    }
  }
}

// The fast grid evaluation (weight tables, piece order, SoA, border routine) agrees with the
// double-precision reference evaluation of the same records at every sample.
TEST(Evaluation, GridMatchesReferenceEvaluation) {
  for (int rate : {2, 4, 7}) {
    const ControlMesh m = accepted("frog-standin");
    CpatchCpuEvaluation eval(m, rate, false);
    eval.execute();
    const Tessellation& out = eval.output();
    const double scale = bbox_diagonal(m);
    for (int q = 0; q < eval.topology().num_quads; ++q) {
      const bool cp = eval.topology().extraordinary[q];
      for (int s = 0; s < rate * rate; ++s) {
        const size_t k = size_t(q) * rate * rate + s;
        const SurfaceCoord c = out.coords[k];
        ASSERT_EQ(c.face, uint32_t(q));
        const PatchRecord record = eval.record(q);
        const PatchPoint p = cp ? cpatch_at(record.data(), c.u, c.v) : bicubic_at(record.data(), c.u, c.v);
        const Vec3f pos = to_vec3(out.positions[k]);
        EXPECT_LE(distance(p.position, to_double(pos)), 2e-6 * scale);
        const auto& du = p.du;
        const auto& dv = p.dv;
        const Vec3d n{du[1] * dv[2] - du[2] * dv[1], du[2] * dv[0] - du[0] * dv[2], du[0] * dv[1] - du[1] * dv[0]};
        const Vec3d unit = (1.0 / std::sqrt(dot(n, n))) * n;
        const Vec3d got = to_double(to_vec3(out.normals[k]));
        EXPECT_GT(dot(unit, got), std::cos(1e-3)) << "quad " << q << " sample " << s;
        EXPECT_NEAR(dot(got, got), 1.0, 1e-5);
      }
    }
  }
}

TEST(Evaluation, SamplesAreAssignedToTheRightPieceAndEveryPieceIsUsed) {
  const SampleGrid grid(9);
  int total = 0;
  for (int p = 0; p < 4; ++p) {
    EXPECT_GT(grid.piece_begin(p + 1), grid.piece_begin(p));
    for (int k = grid.piece_begin(p); k < grid.piece_begin(p + 1); ++k) {
      const int s = grid.piece_order()[k];
      EXPECT_EQ(cpatch_piece(s % 9, s / 9, 9), p);
      ++total;
    }
  }
  EXPECT_EQ(total, 81);
  // The sides run corner k -> corner k+1.
  EXPECT_EQ(grid.side_sample(0, 0), 0);
  EXPECT_EQ(grid.side_sample(1, 0), 8);
  EXPECT_EQ(grid.side_sample(2, 0), 80);
  EXPECT_EQ(grid.side_sample(3, 0), 72);
  EXPECT_EQ(grid.side_sample(3, 8), 0);
}

// The eight-lane path for ordinary quads performs the scalar path's operations lane by lane:
// its output must equal evaluate_quad's bit for bit (so bicubic and c-patch quads share one
// definition of a border, whichever path evaluated them).
TEST(Evaluation, LanePathIsBitIdenticalToThePerQuadPath) {
  for (int rate : {2, 3, 9}) {
    const ControlMesh m = accepted("frog-standin");
    CpatchCpuEvaluation eval(m, rate, false);
    eval.execute();
    const CpatchTopology& t = eval.topology();
    const SampleGrid& grid = eval.grid();
    const size_t per_quad = size_t(rate) * rate;
    PatchScratch scratch(rate * rate);
    std::vector<Point3> positions(per_quad), normals(per_quad);
    int compared = 0;
    for (int q : t.ordinary_quads) {
      const PatchRecord record = eval.record(q);
      evaluate_quad(grid, record.data(), false, t.forward_sides[q], scratch, positions.data(), normals.data());
      for (size_t s = 0; s < per_quad; ++s) {
        ASSERT_EQ(positions[s], eval.output().positions[q * per_quad + s]) << "quad " << q << " sample " << s;
        ASSERT_EQ(normals[s], eval.output().normals[q * per_quad + s]) << "quad " << q << " sample " << s;
      }
      ++compared;
    }
    EXPECT_GT(compared, 100);
  }
}
