#include "harness/bench/machine.h"
#include "harness/core/content_hash.h"
#include "harness/core/errors.h"
#include "harness/gl/context.h"
#include "harness/results/resources.h"

#include "harness/gpu/device_info.h"
#include "harness/gpu/gpu.h"
#include "sdb_gpu_shaders.h"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <elf.h>
#include <link.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <new>
#include <string>
#include <thread>
#include <vector>

namespace sdb {
namespace {

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown";
}

double memory_gib() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  long kb = 0;
  in >> key >> kb;
  return kb / 1048576.0;
}

}  // namespace

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

// The machine as far as it shapes the rows; the probes' bandwidths are measured, not compared.
std::string machine_difference(const MachineInfo& a, const MachineInfo& b) {
  const std::pair<const char*, std::pair<std::string, std::string>> fields[] = {
      {"CPU", {a.cpu_model, b.cpu_model}},
      {"cores", {std::to_string(a.cores), std::to_string(b.cores)}},
      {"Vulkan device", {a.vulkan_device, b.vulkan_device}},
      {"Vulkan driver", {a.vulkan_driver, b.vulkan_driver}},
      {"OpenGL renderer", {a.opengl_renderer, b.opengl_renderer}},
      {"compiler", {a.compiler, b.compiler}},
      {"build type", {a.build_type, b.build_type}}};
  for (const auto& [what, values] : fields)
    if (values.first != values.second) return std::string(what) + " '" + values.first + "', now '" + values.second + "'";
  return "";
}

MachineInfo describe_machine(bool probe_devices) {
  MachineInfo m;
  m.cpu_model = cpu_model();
  m.cores = static_cast<int>(std::thread::hardware_concurrency());
  m.memory_gib = memory_gib();
  m.compiler = std::string("g++ ") + __VERSION__;
  m.build_type = SDB_BUILD_TYPE;
  if (const gl::DeviceInfo g = probe_devices ? gl::probe() : gl::DeviceInfo{}; g.available) {
    m.opengl_renderer = g.renderer;
    m.opengl_version = g.version;
    m.opengl_device_type = g.software ? "cpu" : "gpu";
  }
  if (const gpu::DeviceInfo vk = probe_devices ? gpu::probe() : gpu::DeviceInfo{}; vk.available) {
    m.vulkan_device = vk.name;
    m.vulkan_driver = vk.driver_name + " " + vk.driver_info + " (" + vk.driver_version + ")";
    m.vulkan_api = vk.api_version;
    m.vulkan_device_type = std::string(gpu::to_string(vk.type));
    m.vulkan_memory_gib = double(vk.limits.device_local_bytes) / double(1ull << 30);
  }
  m.git_commit = build_commit();
  return m;
}

namespace {

// The probe's buffer: several times the last-level cache, aligned to and advised as 2 MiB pages.
// With 4 KiB pages, first touch of the 2 GiB this machine's reported L3 (the socket's 508 MiB)
// asks for took 5 s of page faults in a VM, per thread count; huge pages make that 1024 faults.
class ProbeBuffer {
 public:
  ProbeBuffer() {
    const long llc = sysconf(_SC_LEVEL3_CACHE_SIZE);
    bytes_ = std::max<size_t>(size_t(256) << 20, 4 * static_cast<size_t>(std::max(llc, 0L)));
    bytes_ = (bytes_ + k_page - 1) / k_page * k_page;
    data_ = static_cast<float*>(std::aligned_alloc(k_page, bytes_));
    if (!data_) throw std::bad_alloc();
    madvise(data_, bytes_, MADV_HUGEPAGE);  // advice only: without it the probe is just slower to start
  }
  ~ProbeBuffer() { std::free(data_); }
  ProbeBuffer(const ProbeBuffer&) = delete;
  ProbeBuffer& operator=(const ProbeBuffer&) = delete;

  size_t bytes() const { return bytes_; }
  size_t size() const { return bytes_ / sizeof(float); }
  float* data() { return data_; }

 private:
  static constexpr size_t k_page = size_t(2) << 20;
  size_t bytes_ = 0;
  float* data_ = nullptr;
};

void fill(ProbeBuffer& buffer, float value, int threads) {
  float* p = buffer.data();
  if (threads <= 1) {
    std::fill(p, p + buffer.size(), value);
    return;
  }
  tbb::parallel_for(tbb::blocked_range<size_t>(0, buffer.size(), size_t(1) << 20),
                    [&](const tbb::blocked_range<size_t>& r) { std::fill(p + r.begin(), p + r.end(), value); });
}

// Best of five fills of the whole buffer, already touched, in GB/s.
double best_fill_gbs(ProbeBuffer& buffer, int threads) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::max(1, threads));
  double best = 1e30;
  for (int pass = 0; pass < 5; ++pass) {
    const auto start = std::chrono::steady_clock::now();
    fill(buffer, static_cast<float>(pass + 1), threads);
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  volatile float sink = buffer.data()[buffer.size() / 2];  // keep the stores observable
  (void)sink;
  return buffer.bytes() / best / 1e9;
}

}  // namespace

CpuWriteBandwidth measure_write_bandwidth(int threads) {
  ProbeBuffer buffer;
  fill(buffer, 0.0f, threads);  // first touch, in parallel, so page faults are not timed
  return {best_fill_gbs(buffer, 1), best_fill_gbs(buffer, threads)};
}

}  // namespace sdb

namespace sdb {

void add_bandwidth_probes(MachineInfo& m) {
  const CpuWriteBandwidth cpu = measure_write_bandwidth(std::max(1, m.cores));
  m.write_bandwidth_gbs = cpu.one_thread_gbs;
  m.write_bandwidth_mt_gbs = cpu.all_threads_gbs;
  if (!m.vulkan_device.empty()) {
    m.gpu_write_bandwidth_gbs = measure_gpu_write_bandwidth();
    m.gpu_shader_write_bandwidth_gbs = measure_gpu_shader_write_bandwidth();
  }
}

MachineInfo describe_machine_with_probes() {
  MachineInfo m = describe_machine();
  add_bandwidth_probes(m);
  return m;
}

MachineInfo machine_from(const std::string& path, bool devices_probed) {
  MachineInfo here = describe_machine(devices_probed);
  MachineInfo m = read_results(path).machine;
  if (!devices_probed) {
    here.vulkan_device = m.vulkan_device, here.vulkan_driver = m.vulkan_driver;
    here.opengl_renderer = m.opengl_renderer;
  }
  if (const std::string d = machine_difference(m, here); !d.empty() || m.git_commit != here.git_commit)
    throw InputError(path, "describes another machine or build (" + (d.empty() ? "commit " + m.git_commit : d) + ")");
  m.probes_from = path;
  return m;
}

namespace {

// This executable's GNU build id in hex (the linker's note: it changes with every link of changed
// code); "" where the executable has none.
std::string build_id() {
  std::string id;
  dl_iterate_phdr(
      [](dl_phdr_info* info, size_t, void* out) {
        for (int i = 0; i < info->dlpi_phnum; ++i) {
          const ElfW(Phdr)& ph = info->dlpi_phdr[i];
          if (ph.p_type != PT_NOTE) continue;
          const char* p = reinterpret_cast<const char*>(info->dlpi_addr + ph.p_vaddr);
          const char* end = p + ph.p_memsz;
          while (p + sizeof(ElfW(Nhdr)) <= end) {
            const auto* note = reinterpret_cast<const ElfW(Nhdr)*>(p);
            const char* name = p + sizeof(ElfW(Nhdr));
            const char* desc = name + ((note->n_namesz + 3) & ~3u);
            if (note->n_type == NT_GNU_BUILD_ID && note->n_namesz == 4 && std::memcmp(name, "GNU", 4) == 0) {
              auto& hex = *static_cast<std::string*>(out);
              for (unsigned b = 0; b < note->n_descsz; ++b) {
                char byte[3];
                std::snprintf(byte, sizeof byte, "%02x", static_cast<unsigned char>(desc[b]));
                hex += byte;
              }
              return 1;
            }
            p = desc + ((note->n_descsz + 3) & ~3u);
          }
        }
        return 1;  // the first object is the executable: stop there
      },
      &id);
  return id;
}

// The probe file's name: FNV-1a of the boot id, the build id and the variables that pick the
// devices (harness/gpu's no_device_reason lists the Vulkan ones; Mesa's pick the OpenGL driver),
// so a reboot, a rebuild or a test that hides the Vulkan driver finds no file and probes anew.
std::optional<std::string> probe_file_name() {
  std::string key;
  std::ifstream boot("/proc/sys/kernel/random/boot_id");
  if (!std::getline(boot, key) || key.empty()) return std::nullopt;
  const std::string id = build_id();
  if (id.empty()) return std::nullopt;
  key += "\n" + id + "\n" + build_commit();  // the commit is read at run time: a commit keeps the build id
  for (const char* var : {"VK_ICD_FILENAMES", "VK_DRIVER_FILES", "VK_ADD_DRIVER_FILES", gpu::k_device_env,
                          "VK_INSTANCE_LAYERS", "SUBDIVBENCH_VK_VALIDATION", "LIBGL_ALWAYS_SOFTWARE", "GALLIUM_DRIVER",
                          "MESA_LOADER_DRIVER_OVERRIDE", "EGL_PLATFORM", "__EGL_VENDOR_LIBRARY_FILENAMES",
                          "__EGL_VENDOR_LIBRARY_DIRS", "LP_NUM_THREADS", "TBB_NUM_THREADS"}) {
    const char* value = std::getenv(var);
    key += std::string("\n") + var + (value ? "=" + std::string(value) : " unset");
  }
  return "machine-" + hex64(fnv1a_64(key)) + ".json";
}

std::optional<std::filesystem::path> probe_file() {
  const char* folder = std::getenv(kMachineProbesVariable);
  if (!folder || !*folder) return std::nullopt;
  const std::optional<std::string> name = probe_file_name();
  if (!name) return std::nullopt;
  return std::filesystem::path(folder) / *name;
}

}  // namespace

std::optional<MachineInfo> reused_machine_probes() {
  const std::optional<std::filesystem::path> path = probe_file();
  std::error_code ec;
  if (!path || !std::filesystem::exists(*path, ec)) return std::nullopt;
  try {
    return machine_from(path->string(), false);
  } catch (const std::exception&) {
    // Another machine or build, or a file cut short: measured anew, quietly (an error's one line
    // on stderr stays the only one).
    return std::nullopt;
  }
}

MachineInfo describe_machine_or_reuse() {
  if (std::optional<MachineInfo> m = reused_machine_probes()) return *m;
  return describe_machine();
}

void keep_machine_probes(const MachineInfo& m) {
  const std::optional<std::filesystem::path> path = probe_file();
  if (!path || !m.probes_from.empty()) return;
  std::error_code ec;
  std::filesystem::create_directories(path->parent_path(), ec);
  const std::string scratch = path->string() + "." + std::to_string(getpid()) + ".part";
  try {
    ResultsFile probes;
    probes.machine = m;
    probes.created = utc_now();
    write_results(probes, scratch);
    std::filesystem::rename(scratch, *path);
  } catch (const std::exception& e) {  // an unwritable folder costs the next process its probes, nothing else
    std::filesystem::remove(scratch, ec);
    std::fprintf(stderr, "note: machine probes not kept for the next process: %s\n", e.what());
  }
}

namespace {

// GB/s of `bytes` written by what `record` records (given the pass's index, 0..4), the best of
// five submissions timed by timestamp queries; 0 where the queue has no timestamps.
double best_gpu_write_gbs(gpu::Context& ctx, uint64_t bytes, const std::function<void(gpu::Commands&, int)>& record) {
  gpu::GpuTimer timer(ctx);
  if (!timer.supported()) return 0;
  double best_gbs = 0;
  for (int pass = 0; pass < 5; ++pass) {
    ctx.run([&](gpu::Commands& cmd) {
      timer.reset(cmd);
      timer.begin(cmd, gpu::PassKind::Kernel, "write probe");
      record(cmd, pass);
      timer.end(cmd);
    });
    if (auto t = timer.read(); t && t->kernel_ms > 0) best_gbs = std::max(best_gbs, bytes / (t->kernel_ms * 1e-3) / 1e9);
  }
  return best_gbs;
}

}  // namespace

double measure_gpu_write_bandwidth() {
  try {
    auto ctx = gpu::shared_context();
    const uint64_t bytes = std::min<uint64_t>(uint64_t(256) << 20, ctx->limits().max_memory_allocation_size / 2);
    gpu::Buffer buffer = gpu::Buffer::device(*ctx, bytes, gpu::BufferUsage::Storage, "bandwidth probe");
    return best_gpu_write_gbs(*ctx, bytes, [&](gpu::Commands& cmd, int pass) { cmd.fill(buffer, uint32_t(pass + 1)); });
  } catch (const std::exception&) {
    return 0;  // no device: vulkan rows have no bandwidth fraction
  }
}

double measure_gpu_shader_write_bandwidth() {
  try {
    auto ctx = gpu::shared_context();
    const gpu::DeviceLimits& limits = ctx->limits();
    // One binding covers it (lavapipe: 128 MiB), several times any cache.
    const uint64_t bytes = std::min({uint64_t(128) << 20, limits.max_storage_buffer_range & ~uint64_t(127),
                                     limits.max_memory_allocation_size / 2});
    gpu::Buffer buffer = gpu::Buffer::device(*ctx, bytes, gpu::BufferUsage::Storage, "shader store probe");
    auto pipeline = gpu::shared_compute_pipeline(
        *ctx, {sdb_gpu_shaders::get("store_probe.comp"), {gpu::Binding::StorageBuffer}, 2 * sizeof(uint32_t)});
    gpu::DescriptorSet set(*pipeline, {buffer.range()});
    return best_gpu_write_gbs(*ctx, bytes, [&](gpu::Commands& cmd, int pass) {
      const struct {
        uint32_t count;  // vec4s, 8 per invocation
        float value;
      } push{static_cast<uint32_t>(bytes / 16), float(pass + 1)};
      cmd.bind(*pipeline, set);
      cmd.push(push);
      cmd.dispatch(gpu::groups_for(push.count / 8, 256, limits));
    });
  } catch (const std::exception&) {
    return 0;
  }
}

}  // namespace sdb
