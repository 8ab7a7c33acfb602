#include "tests/fuzz/contract.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <vector>

namespace sdb::fuzz {

void finding(const std::string& what) {
  std::fprintf(stderr, "fuzz contract broken: %s\n", what.c_str());
  std::abort();
}

void require_one_line_naming(const std::string& message, const std::string& where) {
  if (message.rfind(where, 0) != 0) finding("InputError does not start with '" + where + "': " + message);
  const std::string reason = message.substr(where.size());
  if (reason.find('\n') != std::string::npos) finding("InputError of more than one line: " + message);
  if (reason.size() <= 2) finding("InputError without a reason: " + message);
}

namespace {

bool finite_point(const Point3& p) { return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]); }

void require_valid_tags(const ControlMesh& m, long nv, long nf) {
  for (const EdgeCrease& c : m.creases) {
    require(c.v0 >= 0 && c.v0 < nv && c.v1 >= 0 && c.v1 < nv, "crease names a vertex out of range");
    require(std::isfinite(c.sharpness) && c.sharpness >= 0, "crease sharpness negative or not finite");
  }
  for (const VertexCorner& c : m.corners) {
    require(c.vertex >= 0 && c.vertex < nv, "corner names a vertex out of range");
    require(std::isfinite(c.sharpness) && c.sharpness >= 0, "corner sharpness negative or not finite");
  }
  for (int h : m.holes) require(h >= 0 && h < nf, "hole names a face out of range");
}

}  // namespace

void require_valid_mesh(const ControlMesh& m) {
  const long nv = static_cast<long>(m.positions.size()), nf = static_cast<long>(m.face_sizes.size());
  require(nv > 0 && nf > 0, "a mesh without vertices or faces was returned");
  for (const Point3& p : m.positions) require(finite_point(p), "a coordinate is NaN or Inf");
  long corners = 0;
  for (int n : m.face_sizes) {
    require(n >= 3, "a face of fewer than 3 vertices");
    corners += n;
  }
  require(corners == static_cast<long>(m.face_vertices.size()), "face sizes do not add up to the face-vertex list");
  for (int v : m.face_vertices) require(v >= 0 && v < nv, "a face names a vertex out of range");
  require(m.face_lines.empty() || static_cast<long>(m.face_lines.size()) == nf, "face lines do not match the faces");
  require_valid_tags(m, nv, nf);
}

namespace {

struct InputFiles {
  std::vector<std::string> paths;
  ~InputFiles() {
    std::error_code ec;
    for (const std::string& p : paths) std::filesystem::remove(p, ec);
  }
};

}  // namespace

std::string scratch_path(const std::string& suffix) {
  static InputFiles files;
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("subdivbench-fuzz-" + std::to_string(::getpid()) + suffix)).string();
  if (std::find(files.paths.begin(), files.paths.end(), path) == files.paths.end()) files.paths.push_back(path);
  return path;
}

std::string write_input_file(std::string_view data, const std::string& extension) {
  const std::string path = scratch_path(extension);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(data.data(), static_cast<std::streamsize>(data.size()));
  out.close();
  if (!out) finding("cannot write the input file " + path);
  return path;
}

}  // namespace sdb::fuzz
