// The OpenGL backend's context: a headless OpenGL 4.3+ core context made with EGL (Mesa's
// surfaceless platform, else the default display with a pbuffer), for peers that evaluate with
// OpenGL (OpenSubdiv's GLComputeEvaluator). libEGL is opened at run time, as harness/gpu opens
// the Vulkan loader: every executable starts where EGL or GL is missing, and the `opengl` backend
// is then reported unavailable with the reason, not failed. README.md.
#pragma once

#include <GL/glcorearb.h>

#include <memory>
#include <stdexcept>
#include <string>

namespace sdb::gl {

// No EGL, no display, no GL 4.3 core context: the backend is unavailable.
class Unavailable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The GL entry points the harness and its peers call themselves (OpenSubdiv loads its own).
struct Functions {
  PFNGLGETSTRINGPROC GetString = nullptr;
  PFNGLGETERRORPROC GetError = nullptr;
  PFNGLGETINTEGERVPROC GetIntegerv = nullptr;
  PFNGLFINISHPROC Finish = nullptr;
  PFNGLGENQUERIESPROC GenQueries = nullptr;
  PFNGLDELETEQUERIESPROC DeleteQueries = nullptr;
  PFNGLQUERYCOUNTERPROC QueryCounter = nullptr;
  PFNGLGETQUERYOBJECTUI64VPROC GetQueryObjectui64v = nullptr;
  PFNGLBINDBUFFERPROC BindBuffer = nullptr;
  PFNGLBUFFERSUBDATAPROC BufferSubData = nullptr;
  PFNGLGETBUFFERSUBDATAPROC GetBufferSubData = nullptr;
  PFNGLMEMORYBARRIERPROC MemoryBarrier = nullptr;
};

struct DeviceInfo {
  bool available = false;
  std::string reason;                      // why not, when unavailable
  std::string renderer, version, vendor;   // GL_RENDERER, GL_VERSION, GL_VENDOR
  std::string platform;                    // "surfaceless" or "default display, pbuffer"
  // The renderer is one of Mesa's software rasterizers (llvmpipe, softpipe): OpenGL on the CPU
  // cores, not a GPU. OpenGL has no device type; these are the renderer names Mesa gives them.
  bool software = false;
};

// A context current on the thread that made it (GL calls must come from that thread: the
// benchmark loop and the harness's runs are on the main thread).
class Context {
 public:
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;
  const DeviceInfo& info() const { return info_; }
  const Functions& functions() const { return functions_; }
  // Throws std::runtime_error naming `doing` when GL has an error flag set (and clears it).
  void check(const char* doing) const;

 private:
  friend std::shared_ptr<Context> shared_context();
  Context();
  struct Egl;
  std::unique_ptr<Egl> egl_;
  DeviceInfo info_;
  Functions functions_;
};

// The process-wide context, made on first use; throws Unavailable with the reason.
std::shared_ptr<Context> shared_context();

// Whether a context can be made here, and the renderer; tries once per process.
DeviceInfo probe();

// One line: "llvmpipe (LLVM 15.0.6, 256 bits), OpenGL 4.5 (Core Profile) Mesa 22.3.6".
std::string summary(const DeviceInfo& info);

}  // namespace sdb::gl
