#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "harness/core/errors.h"
#include "harness/core/input_error_of_file.h"
#include "harness/mesh/facts.h"
#include "harness/mesh/mesh_io.h"
#include "harness/mesh/placement.h"
#include "harness/mesh/quadrangulate.h"
#include "harness/mesh/split_polygons.h"

namespace fs = std::filesystem;
using namespace sdb;

namespace {

std::string corpus(const std::string& rel) {
  const fs::path p = fs::path(SDB_SOURCE_DIR) / ".." / "shared" / "datasets" / rel;
  return fs::exists(p) ? p.string() : std::string();
}

// The message of the InputError `text` raises when read as `name`, or "" when it reads fine.
std::string obj_error(const std::string& text) {
  try {
    parse_obj(text, "bad.obj");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// What read_mesh says of a file `name` holding `text` (PLY through its check and OpenMesh).
std::string file_error(const std::string& name, const std::string& text) {
  return input_error_of_file(name, text, [](const std::string& path) { read_mesh(path); });
}

const char* kQuad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";

}  // namespace

TEST(ObjReader, ReadsPolygonsSlashSyntaxAndNegativeIndices) {
  const ControlMesh m = parse_obj(std::string(kQuad) + "vt 0 0\nvn 0 0 1\nf 1/1/1 2//1 3/1 -1\n", "q.obj");
  ASSERT_EQ(num_faces(m), 1);
  EXPECT_EQ(m.face_sizes[0], 4);
  EXPECT_EQ(m.face_vertices, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(m.face_lines, (std::vector<int>{7}));
}

TEST(ObjReader, ReadsOpenSubdivTags) {
  const ControlMesh m = parse_obj(std::string(kQuad) +
                                      "v 0 0 1\nf 1 2 3 4\nf 1 5 2\n"
                                      "t crease 2/1/0 0 1 2.5\nt corner 1/1/0 4 3.0\nt hole 1/0/0 1\n"
                                      "t interpolateboundary 1/0/0 1\nt creasemethod 0/0/1 chaikin\n"
                                      "t vertexedit 1/0/0 0\n",
                                  "tags.obj");
  ASSERT_EQ(m.creases.size(), 1u);
  EXPECT_EQ(m.creases[0].v0, 0);
  EXPECT_EQ(m.creases[0].v1, 1);
  EXPECT_FLOAT_EQ(m.creases[0].sharpness, 2.5f);
  ASSERT_EQ(m.corners.size(), 1u);
  EXPECT_EQ(m.corners[0].vertex, 4);
  EXPECT_EQ(m.holes, (std::vector<int>{1}));
  EXPECT_EQ(m.boundary, BoundaryRule::EdgeAndCorner);
  EXPECT_EQ(m.crease_method, CreaseMethod::Chaikin);
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_NE(m.warnings[0].find("vertexedit"), std::string::npos);
}

// One malformed input per check; each message names the file and line.
struct Malformed {
  const char* what;
  std::string text;
  const char* expect;
};

TEST(ObjReader, RefusesMalformedInputWithFileAndLine) {
  const std::string q = kQuad;
  const std::vector<Malformed> cases = {
      {"malformed number", "v 0 0 0\nv 1 abc 0\n", "bad.obj:2: malformed number 'abc'"},
      {"too few coordinates", "v 0 0\n", "bad.obj:1: vertex needs 3 coordinates"},
      {"NaN coordinate", q + "v nan 0 0\nf 1 2 3\n", "bad.obj:5: NaN or Inf coordinate"},
      {"Inf coordinate", q + "v 0 inf 0\nf 1 2 3\n", "bad.obj:5: NaN or Inf coordinate"},
      {"index out of range", q + "f 1 2 9\n", "bad.obj:5: vertex index 9 out of range (mesh has 4 vertices)"},
      {"index zero", q + "f 0 1 2\n", "bad.obj:5: vertex index 0"},
      {"relative index before start", q + "f -1 -2 -7\n", "bad.obj:5: relative index '-7' reaches before the first vertex"},
      {"fewer than 3 vertices", q + "f 1 2\n", "bad.obj:5: face has 2 vertices; at least 3 needed"},
      {"malformed face index", q + "f 1 2 x\n", "bad.obj:5: malformed integer 'x'"},
      {"empty: no faces", q, "bad.obj: empty mesh: no faces"},
      {"empty: nothing", "# nothing\n", "bad.obj: empty mesh: no vertices"},
      {"crease on a non-edge", q + "f 1 2 3 4\nt crease 2/1/0 0 2 1.0\n", "bad.obj:6: crease tag names (0,2)"},
      {"tag count mismatch", q + "f 1 2 3 4\nt crease 2/1/0 0 1\n", "bad.obj:6: tag 'crease' announces 3 arguments"},
      {"corner out of range", q + "f 1 2 3 4\nt corner 1/1/0 9 1.0\n", "bad.obj:6: corner tag names vertex 9"},
      {"hole out of range", q + "f 1 2 3 4\nt hole 1/0/0 3\n", "bad.obj:6: hole tag names face 3"},
  };
  for (const auto& c : cases) {
    const std::string msg = obj_error(c.text);
    EXPECT_EQ(msg.rfind(c.expect, 0), 0u) << c.what << ": got '" << msg << "'";
    EXPECT_EQ(msg.find('\n'), std::string::npos) << c.what << ": message must be one line";
  }
}

TEST(ReadMesh, MissingFileAndDirectory) {
  EXPECT_THROW(
      {
        try {
          read_mesh("/nonexistent/x.obj");
        } catch (const InputError& e) {
          EXPECT_STREQ(e.what(), "/nonexistent/x.obj: no such file");
          throw;
        }
      },
      InputError);
  const fs::path dir = fs::temp_directory_path() / "sdb_dir.obj";
  fs::create_directories(dir);
  EXPECT_THROW(read_mesh(dir.string()), InputError);
}

TEST(ReadMesh, OffThroughOpenMeshKeepsFileData) {
  const fs::path p = fs::temp_directory_path() / "sdb_quad.off";
  std::ofstream(p) << "OFF\n# comment\n5 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n4 0 1 2 3\n3 0 4 1\n";
  const ControlMesh m = read_mesh(p.string());
  EXPECT_EQ(num_vertices(m), 5);
  EXPECT_EQ(m.face_sizes, (std::vector<int>{4, 3}));
  EXPECT_EQ(m.face_lines, (std::vector<int>{9, 10}));
}

TEST(ReadMesh, OffErrorsNameTheLine) {
  const fs::path p = fs::temp_directory_path() / "sdb_bad.off";
  std::ofstream(p) << "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n";
  try {
    read_mesh(p.string());
    FAIL() << "out-of-range index accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), p.string() + ":6: vertex index 7 out of range (mesh has 3 vertices)");
  }
  std::ofstream(p) << "OFF\n3 1 0\n0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n";
  try {
    read_mesh(p.string());
    FAIL() << "malformed number accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), p.string() + ":4: malformed number 'x'");
  }
}

// Non-manifold edges and inconsistent orientation are facts of a mesh, refused by schemes that
// need a manifold: the message names the line of the face that breaks it.
TEST(Facts, NonManifoldAndOrientationAreReportedWithTheLine) {
  const std::string fan = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n";
  const ControlMesh nm = parse_obj(fan, "fan.obj");
  EXPECT_EQ(compute_facts(nm).non_manifold_edges, 1);
  try {
    require_manifold(nm, "test-scheme");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("fan.obj:8: non-manifold edge (1,2) shared by 3 faces", 0), 0u) << e.what();
  }
  const ControlMesh degenerate = parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 4 3\nf 1 3 3 2\n", "deg.obj");
  EXPECT_EQ(compute_facts(degenerate).degenerate_faces, 1);
  try {
    require_manifold(degenerate, "test-scheme");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("deg.obj:6: vertex 3 repeated in one face; test-scheme needs", 0), 0u) << e.what();
  }
  const ControlMesh flip = parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nf 1 2 3\nf 1 2 4\n", "flip.obj");
  const MeshFacts f = compute_facts(flip);
  EXPECT_EQ(f.inconsistent_edges, 1);
  EXPECT_EQ(f.genus, -1);
  try {
    require_manifold(flip, "test-scheme");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("flip.obj:6: inconsistent orientation", 0), 0u) << e.what();
  }
}

TEST(Facts, SpotControlMesh) {
  const std::string path = corpus("crane/spot_control.obj");
  if (path.empty()) GTEST_SKIP() << "shared corpus not found beside the checkout";
  const MeshFacts f = compute_facts(read_mesh(path));
  EXPECT_EQ(f.vertices, 188);
  EXPECT_EQ(f.face_sizes, (std::map<int, int>{{3, 4}, {4, 160}, {5, 16}}));
  EXPECT_TRUE(f.closed);
  EXPECT_EQ(f.genus, 0);
  EXPECT_EQ(f.components, 1);
  EXPECT_EQ(f.boundary_edges, 0);
  EXPECT_EQ(f.euler, 2);
}

TEST(Facts, CreaseTaggedShapeKeepsSharpness) {
  const std::string path = corpus("opensubdiv/catmark_chaikin1.obj");
  if (path.empty()) GTEST_SKIP() << "shared corpus not found beside the checkout";
  const ControlMesh m = read_mesh(path);
  ASSERT_FALSE(m.creases.empty());
  EXPECT_EQ(m.crease_method, CreaseMethod::Chaikin);
  bool found = false;
  for (const auto& c : m.creases) found |= c.v0 == 0 && c.v1 == 1 && c.sharpness == 5.0f;
  EXPECT_TRUE(found);
  // Through one Catmull-Clark step the crease survives at sharpness 5 - 1 (Chaikin varies it).
  const ControlMesh q = quadrangulate(m);
  float max_sharp = 0;
  for (const auto& c : q.creases) max_sharp = std::max(max_sharp, c.sharpness);
  EXPECT_GT(max_sharp, 3.0f);
  EXPECT_LT(max_sharp, 5.0f);
}

TEST(Quadrangulate, SpotBecomesAllQuadsWithTheSameTopologyClass) {
  const std::string path = corpus("crane/spot_control.obj");
  if (path.empty()) GTEST_SKIP() << "shared corpus not found beside the checkout";
  const ControlMesh m = read_mesh(path);
  const ControlMesh q = quadrangulate(m);
  const MeshFacts f = compute_facts(q);
  EXPECT_TRUE(f.all_quads);
  // 4 triangles -> 12 quads, 160 quads -> 640, 16 pentagons -> 80.
  EXPECT_EQ(f.faces, 12 + 640 + 80);
  EXPECT_TRUE(f.closed);
  EXPECT_EQ(f.genus, 0);
  // Quad face lines point back to the input line of their parent face.
  ASSERT_EQ(q.face_lines.size(), q.face_sizes.size());
  EXPECT_EQ(q.face_lines[0], m.face_lines[0]);
  EXPECT_EQ(q.face_lines.back(), m.face_lines.back());
}

// What the readers must not do silently (issue 14): a byte-order mark drops no vertex, and header
// counts are held to the content.
TEST(ReadMesh, ByteOrderMarkIsNotPartOfTheFirstLine) {
  const ControlMesh m = parse_obj("\xEF\xBB\xBFv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "bom.obj");
  EXPECT_EQ(num_vertices(m), 3);
  EXPECT_EQ(num_faces(m), 1);
}

TEST(ReadMesh, OffFaceLineMustHoldTheVerticesItAnnounces) {
  const std::string off = "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n9 0 2 3\n";
  try {
    parse_off(off, "f.off");
    FAIL() << "a face line announcing 9 vertices with 3 was read";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "f.off:8: face announces 9 vertices, line has 3");
  }
  EXPECT_THROW(parse_off("OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n", "more.off"), InputError);
  EXPECT_THROW(parse_off("OFF\n4 3 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n", "fewer.off"), InputError);
}

TEST(ReadMesh, TagIndicesNeverWrapIntoAnotherVertex) {
  const std::string cube = "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n";
  EXPECT_THROW(parse_obj(cube + "t crease 2/1/0 4294967296 1 2.0\n", "w.obj"), InputError);
  EXPECT_THROW(parse_obj(cube + "t crease 9223372036854775807/1/0 0 1 2.0\n", "o.obj"), InputError);
  EXPECT_THROW(parse_obj(cube + "f 1 2 -9223372036854775808\n", "m.obj"), InputError);
}

namespace {

// Binary OFF in OpenMesh's layout: little-endian int32 counts, float32 xyz, int32 size + indices.
std::string binary_off(int32_t nv, int32_t nf, const std::vector<std::vector<int32_t>>& faces, int vertices_written) {
  std::string s = "OFF BINARY\n";
  auto put = [&](auto x) { s.append(reinterpret_cast<const char*>(&x), 4); };
  put(nv), put(nf), put(int32_t(0));
  for (int v = 0; v < vertices_written; ++v) put(float(v)), put(float(v % 2)), put(float(v / 2));
  for (const auto& f : faces) {
    put(int32_t(f.size()));
    for (int32_t i : f) put(i);
  }
  return s;
}

std::string binary_off_error(const std::string& data) {
  try {
    parse_binary_off(data, "b.off");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(ReadMesh, BinaryOffReadsOpenMeshLayout) {
  ASSERT_TRUE(is_binary_off(binary_off(4, 2, {}, 0)));
  const ControlMesh m = parse_binary_off(binary_off(4, 2, {{0, 1, 2}, {0, 2, 3}}, 4), "b.off");
  EXPECT_EQ(num_vertices(m), 4);
  EXPECT_EQ(m.face_sizes, (std::vector<int>{3, 3}));
  EXPECT_EQ(m.face_vertices, (std::vector<int>{0, 1, 2, 0, 2, 3}));
  EXPECT_EQ(m.positions[3], (Point3{3, 1, 1}));
}

// The fuzzer's first finding: OpenMesh reserved memory for whatever the header announced.
TEST(ReadMesh, BinaryOffCountsAreHeldToTheFileSize) {
  EXPECT_NE(binary_off_error(binary_off(2000000000, 2, {{0, 1, 2}}, 4)).find("more than the file's"), std::string::npos);
  EXPECT_NE(binary_off_error(binary_off(4, 3, {{0, 1, 2}, {0, 2, 3}}, 4)).find("announces 4 vertices and 3 faces"),
            std::string::npos);
  EXPECT_NE(binary_off_error(binary_off(4, 1, {{0, 1, 2000000000}}, 4)).find("face 0: vertex index 2000000000 out of range"),
            std::string::npos);
  EXPECT_NE(binary_off_error(binary_off(4, 1, {{0, 1}}, 4) + std::string(8, '\0')).find("face 0 has 2 vertices"),
            std::string::npos);
  // "BINARY" inside another token is not the binary keyword: the ASCII reader refuses the count.
  const std::string lying = "OFF\t777777777777777733BINARY\t\x13";
  EXPECT_FALSE(is_binary_off(lying));
  EXPECT_THROW(parse_off(lying, "x.off"), InputError);
}

// tests/fuzz: an OBJ index of 2^31 is out of range; quoting it 1-based overflowed an int.
TEST(ObjReader, IndexAtIntLimitIsQuotedAsWritten) {
  EXPECT_NE(obj_error(std::string(kQuad) + "f 1 2 2147483648\n").find("vertex index 2147483648 out of range"),
            std::string::npos);
}

// tests/fuzz: OFF counts whose sum overflows a long were compared after adding them.
TEST(ReadMesh, OffCountsThatOverflowTheirSumAreRefused) {
  try {
    parse_off("OFF 8888000000000000000 2122324063000000000\n0 0 0\n", "big.off");
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("header announces 8888000000000000000 vertices"), std::string::npos) << e.what();
  }
}

// tests/fuzz: OpenMesh loops forever on a PLY format line whose version is not a number.
TEST(ReadMesh, PlyVersionOtherThanOneIsRefusedBeforeOpenMesh) {
  const std::string e = file_error("sdb_mesh_test_version.ply",
                                   "ply\nformat binary_little_endian o10\nelement vertex 0\nproperty float x\n"
                                   "property float y\nproperty float z\nelement face 0\n"
                                   "property list uchar int vertex_indices\nend_header\n");
  EXPECT_NE(e.find(":2: unknown PLY version"), std::string::npos) << e;
}

// tests/fuzz: an element without properties takes no bytes, so a binary body could not bound its
// count and the walk over 9e18 empty instances hung.
TEST(ReadMesh, PlyElementWithoutPropertiesIsRefused) {
  const std::string e = file_error("sdb_mesh_test_empty_element.ply",
                                   "ply\nformat binary_little_endian 1.0\nelement vertex 0\nproperty float x\n"
                                   "property float y\nproperty float z\nelement junk 9000000000000000000\n"
                                   "element face 0\nproperty list uchar int vertex_indices\nend_header\n");
  EXPECT_NE(e.find(":7: element 'junk' announces 9000000000000000000 instances but no properties"), std::string::npos)
      << e;
}

// tests/fuzz: a form feed splits a word for OpenMesh but not for us, and a NUL is part of one for
// OpenMesh; it then looped on a count it could not parse.
TEST(ReadMesh, PlyHeaderControlBytesAreRefused) {
  const std::string e = file_error("sdb_mesh_test_control.ply",
                                   "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\n"
                                   "property float z\nelement ed\fge 0\nproperty int a\nelement face 0\n"
                                   "property list uchar int vertex_indices\nend_header\n");
  EXPECT_NE(e.find(":7: byte 12 in the header"), std::string::npos) << e;
}

// R1 for quad/triangle schemes: a pentagon becomes a quad and a triangle, a hexagon two quads, a
// heptagon two quads and a triangle, fanned from the first corner; quads and triangles stay; a
// hole's parts are holes and every part keeps its face's line.
TEST(SplitPolygons, FansQuadsAndALastTriangleFromTheFirstCorner) {
  ControlMesh m;
  m.positions.resize(8);
  m.face_sizes = {5, 6, 7, 3};
  m.face_vertices = {0, 1, 2, 3, 4, 0, 1, 2, 3, 4, 5, 0, 1, 2, 3, 4, 5, 6, 0, 1, 7};
  m.face_lines = {10, 11, 12, 13};
  m.holes = {1};
  const ControlMesh s = split_polygons(m);
  EXPECT_EQ(s.face_sizes, (std::vector<int>{4, 3, 4, 4, 4, 4, 3, 3}));
  EXPECT_EQ(s.face_vertices, (std::vector<int>{0, 1, 2, 3, 0, 3, 4, 0, 1, 2, 3, 0, 3, 4, 5, 0, 1, 2, 3, 0, 3, 4, 5,
                                               0, 5, 6, 0, 1, 7}));
  EXPECT_EQ(s.face_lines, (std::vector<int>{10, 10, 11, 11, 12, 12, 12, 13}));
  EXPECT_EQ(s.holes, (std::vector<int>{2, 3}));
}

// Issue 45: what C calls blanks separate tokens, every line end ends a line, and a coordinate too
// small for a float is a number (before: the cube read as an empty mesh, or 'number out of range').
TEST(ObjReader, ReadsEveryBlankEveryLineEndAndDenormals) {
  const std::string cube = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                           "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
  std::string ff = cube, cr = cube;
  for (size_t i = 0; (i = ff.find("v ", i)) != std::string::npos;) ff[i + 1] = '\f', ++i;
  for (size_t i = 0; (i = ff.find("f ", i)) != std::string::npos;) ff[i + 1] = '\v', ++i;
  std::replace(cr.begin(), cr.end(), '\n', '\r');
  for (const std::string& text : {ff, cr}) {
    const ControlMesh m = parse_obj(text, "cube.obj");
    EXPECT_EQ(num_vertices(m), 8);
    EXPECT_EQ(m.face_vertices, parse_obj(cube, "cube.obj").face_vertices);
  }
  EXPECT_EQ(parse_obj(cr + "f 1 2 3\r", "cube.obj").face_lines.back(), 15);
  EXPECT_NE(obj_error(cr + "f 1 2 99\r").find("bad.obj:15:"), std::string::npos) << "CR lines are counted";
  const ControlMesh tiny = parse_obj("v -1e-50 1e-40 1e-400\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "t.obj");
  EXPECT_EQ(tiny.positions[0][0], 0.0f);
  EXPECT_FALSE(std::signbit(tiny.positions[0][0])) << "one zero";
  EXPECT_GT(tiny.positions[0][1], 0.0f);
  EXPECT_LT(tiny.positions[0][1], 1.2e-38f);
  EXPECT_NE(obj_error("v 1e39 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").find("out of range"), std::string::npos);
}

// A tag given twice is one tag, the last sharpness holding (Far sets it once per tag, in order).
TEST(ObjReader, RepeatedTagsAreOneTagWithAWarning) {
  const ControlMesh m = parse_obj(std::string(kQuad) + "f 1 2 3 4\nt crease 2/1/0 0 1 2.0\nt crease 2/1/0 1 0 3.0\n"
                                                       "t hole 1/0/0 0\nt hole 1/0/0 0\nt corner 1/1/0 2 1.0\nt corner 1/1/0 2 4.0\n",
                                  "twice.obj");
  ASSERT_EQ(m.creases.size(), 1u);
  EXPECT_FLOAT_EQ(m.creases[0].sharpness, 3.0f);
  EXPECT_EQ(m.holes, (std::vector<int>{0}));
  ASSERT_EQ(m.corners.size(), 1u);
  EXPECT_FLOAT_EQ(m.corners[0].sharpness, 4.0f);
  ASSERT_EQ(m.warnings.size(), 3u);
  EXPECT_NE(m.warnings[0].find("twice.obj:7: crease on edge (1,0) given again"), std::string::npos) << m.warnings[0];
  const MeshFacts f = compute_facts(m);
  EXPECT_EQ(f.creased_edges, 1);
  EXPECT_EQ(f.holes, 1);
}

// A uint index past INT_MAX is quoted as written, ASCII and binary (OpenMesh read it as -1).
TEST(ReadMesh, PlyUintIndexIsQuotedAsWritten) {
  const std::string head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                           "element face 1\nproperty list uchar uint vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n";
  EXPECT_NE(file_error("u.ply", head + "3 0 1 4294967295\n").find("u.ply:13: vertex index 4294967295 out of range"),
            std::string::npos)
      << file_error("u.ply", head + "3 0 1 4294967295\n");
  std::string cr = head + "3 0 1 2\n";
  std::replace(cr.begin(), cr.end(), '\n', '\r');
  EXPECT_EQ(file_error("cr.ply", cr), "") << "CR-only lines read as the LF file";
}

// Pinches and bowties: a vertex whose faces form two fans is non-manifold, and a boundary loop
// runs through one fan (before: two cubes sharing a vertex were a closed genus-0 manifold; a
// bowtie's two triangles one boundary loop).
TEST(Facts, PinchedVerticesAndBowtieLoops) {
  const ControlMesh bowtie = parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nv -1 0 0\nv 0 -1 0\nf 1 2 3\nf 1 4 5\n", "bowtie.obj");
  const MeshFacts f = compute_facts(bowtie);
  EXPECT_EQ(f.non_manifold_vertices, 1);
  EXPECT_EQ(f.boundary_loops, 2);
  EXPECT_FALSE(f.manifold());
  EXPECT_EQ(f.genus, -1);
  try {
    require_manifold(bowtie, "s");
    ADD_FAILURE() << "a pinch passed require_manifold";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bowtie.obj:7: non-manifold vertex 1"), std::string::npos) << e.what();
  }
  const ControlMesh strip = parse_obj(std::string(kQuad) + "v 2 0 0\nv 2 1 0\nf 1 2 3 4\nf 2 5 6 3\n", "strip.obj");
  EXPECT_EQ(compute_facts(strip).non_manifold_vertices, 0);
  EXPECT_EQ(compute_facts(strip).boundary_loops, 1);
}

// Every run judges the mesh placed at unit size: a scaled copy, or one moved by ten diagonals,
// places onto the original (within float's rounding of the copy), and geometry nothing can be
// judged on is refused naming what is degenerate.
TEST(Placement, ScaledAndMovedCopiesPlaceOntoTheOriginal) {
  const ControlMesh cube = parse_obj("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                                     "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\nv 1e4 1e4 1e4\n",
                                     "cube.obj");
  const ControlMesh placed = placed_mesh(cube);
  EXPECT_NEAR(used_bounds(placed).diagonal(), 0.866, 1e-3) << "the unused far vertex is not in the bounds";
  for (double scale : {1e-30, 1e-6, 1e6, 1e10, 1e36})
    for (double offset : {0.0, 10 * scale}) {
      ControlMesh copy = cube;
      for (auto& p : copy.positions)
        for (float& x : p) x = static_cast<float>(x * scale + offset);
      const ControlMesh q = placed_mesh(copy);
      // Centred alike and within a factor of two in size (scaled by a power of two, exact in
      // float): compared at one size, they agree to float's rounding of the copy.
      const double size = used_bounds(placed).diagonal() / used_bounds(q).diagonal();
      EXPECT_GT(size, 0.5) << scale;
      EXPECT_LT(size, 2.0) << scale;
      for (int v = 0; v < 8; ++v)
        for (int k = 0; k < 3; ++k)
          EXPECT_NEAR(q.positions[v][k] * size, placed.positions[v][k], offset > 0 ? 1e-5 : 1e-6) << scale << " " << offset;
    }
}

TEST(Placement, DegenerateGeometryIsNamed) {
  const std::string faces = "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
  auto why = [&](const std::string& vertices) { return degenerate_geometry(parse_obj(vertices + faces, "d.obj")).value_or(""); };
  std::string point, line;
  for (int v = 0; v < 8; ++v) point += "v 1 1 1\n", line += "v " + std::to_string(v) + " " + std::to_string(2 * v) + " 0\n";
  EXPECT_NE(why(point).find("d.obj: degenerate geometry: the 8 vertices the faces use all lie at one point"), std::string::npos);
  EXPECT_NE(why(line).find("collapsed to a line"), std::string::npos) << why(line);
  EXPECT_EQ(why("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"), "")
      << "a flat, closed mesh has faces of area";
  const ControlMesh strips = parse_obj("v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0\nv 2 1 0\nf 1 2 3\nf 4 5 6\n", "z.obj");
  EXPECT_NE(degenerate_geometry(strips).value_or("").find("every face has zero area"), std::string::npos);
  const ControlMesh coincident = parse_obj(std::string(kQuad) + "v 5 5 5\nv 5 5 5\nv 5 5 5\nf 1 2 3 4\nf 5 6 7\n", "c.obj");
  EXPECT_NE(degenerate_geometry(coincident).value_or("").find("c.obj:9: degenerate geometry: the face's 3 vertices lie at one point"),
            std::string::npos);
  EXPECT_THROW(placed_mesh(coincident), InputError);
}
