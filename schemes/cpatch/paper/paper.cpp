// The c-patch paper's tables (TABLES.md): ni2008-table4 and ni2008-table5 (frames per second of the
// 2-pass and 1-pass variants in render mode, fps.cpp) and ni2008-fig12 (deviation from the
// Catmull-Clark limit with heat maps, fig12.cpp).
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "harness/core/paper_table.h"
#include "harness/gpu/gpu.h"
#include "harness/mesh/facts.h"
#include "schemes/cpatch/paper/paper.h"

namespace sdb {

std::vector<PaperTable> cpatch_paper_tables() {
  return {{"ni2008-table4", "GPU Smoothing of Quad Meshes, Table 4: 2-pass frames per second", cpatch::run_table4},
          {"ni2008-table5", "GPU Smoothing of Quad Meshes, Table 5: 1-pass (geometry shader) frames per second",
           cpatch::run_table5},
          {"ni2008-fig12", "GPU Smoothing of Quad Meshes, Figure 12: c-patch surface against the Catmull-Clark limit",
           cpatch::run_fig12}};
}

namespace cpatch {

std::string fixed(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

std::string mesh_shape(MeasureContext& context, const std::string& mesh, const ControlMesh& quads) {
  const MeshFacts f = compute_facts(context.mesh(mesh));
  std::string shape = "(" + std::to_string(f.vertices) + ", " + std::to_string(f.faces) + ", " +
                      fixed(100 * f.extraordinary_quad_fraction, 0) + "%)";
  if (!f.all_quads) shape += ", " + std::to_string(num_faces(quads)) + " quads after one Catmull-Clark step";
  return shape;
}

std::string device_line() {
  const gpu::DeviceInfo info = gpu::probe();
  if (!info.available) return "no Vulkan device (" + info.reason + ")";
  std::string line = info.name + ", " + info.driver_name + " " + info.driver_info + ", Vulkan " + info.api_version;
  if (info.type == gpu::DeviceType::Cpu)
    line += ". This is a CPU implementation of Vulkan (Mesa's lavapipe: llvmpipe rasterizes on the CPU cores), "
            "so absolute frames per second are not comparable with the paper's 2008 DirectX 10 GPUs; compare "
            "the shape across N and meshes, and the ratios";
  return line;
}

std::string publish(const PaperTableOptions& options, const std::string& id, const std::string& markdown,
                    std::ostream& out) {
  std::filesystem::create_directories(options.out_dir);
  const std::string path = (std::filesystem::path(options.out_dir) / (id + ".md")).string();
  std::ofstream file(path);
  file << markdown;
  if (!file) throw std::runtime_error("cannot write " + path);
  out << markdown << "\nwrote " << path << "\n";
  return path;
}

}  // namespace cpatch
}  // namespace sdb
