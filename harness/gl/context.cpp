#include "harness/gl/context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <dlfcn.h>

#include <cstdio>
#include <cstring>
#include <mutex>

namespace sdb::gl {
namespace {

std::string egl_error(const char* what, EGLint code) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%s failed (EGL error 0x%04x)", what, static_cast<unsigned>(code));
  return buf;
}

}  // namespace

// libEGL's entry points, looked up at run time.
struct Context::Egl {
  void* library = nullptr;
  PFNEGLGETPROCADDRESSPROC GetProcAddress = nullptr;
  PFNEGLQUERYSTRINGPROC QueryString = nullptr;
  PFNEGLGETDISPLAYPROC GetDisplay = nullptr;
  PFNEGLINITIALIZEPROC Initialize = nullptr;
  PFNEGLTERMINATEPROC Terminate = nullptr;
  PFNEGLBINDAPIPROC BindAPI = nullptr;
  PFNEGLCHOOSECONFIGPROC ChooseConfig = nullptr;
  PFNEGLCREATECONTEXTPROC CreateContext = nullptr;
  PFNEGLDESTROYCONTEXTPROC DestroyContext = nullptr;
  PFNEGLCREATEPBUFFERSURFACEPROC CreatePbufferSurface = nullptr;
  PFNEGLDESTROYSURFACEPROC DestroySurface = nullptr;
  PFNEGLMAKECURRENTPROC MakeCurrent = nullptr;
  PFNEGLGETERRORPROC GetError = nullptr;
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  EGLSurface surface = EGL_NO_SURFACE;

  template <typename F>
  void load(F& f, const char* name) {
    f = reinterpret_cast<F>(dlsym(library, name));
    if (!f) throw Unavailable(std::string("libEGL.so.1 lacks ") + name);
  }

  ~Egl() {
    if (display != EGL_NO_DISPLAY) {
      MakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      if (context != EGL_NO_CONTEXT) DestroyContext(display, context);
      if (surface != EGL_NO_SURFACE) DestroySurface(display, surface);
      Terminate(display);
    }
    // libEGL stays loaded: drivers register exit handlers inside it.
  }

  void open() {
    library = dlopen("libEGL.so.1", RTLD_NOW | RTLD_LOCAL);
    if (!library) throw Unavailable("no EGL (libEGL.so.1 cannot be opened; Debian: libegl1, libegl-mesa0)");
    load(GetProcAddress, "eglGetProcAddress");
    load(QueryString, "eglQueryString");
    load(GetDisplay, "eglGetDisplay");
    load(Initialize, "eglInitialize");
    load(Terminate, "eglTerminate");
    load(BindAPI, "eglBindAPI");
    load(ChooseConfig, "eglChooseConfig");
    load(CreateContext, "eglCreateContext");
    load(DestroyContext, "eglDestroyContext");
    load(CreatePbufferSurface, "eglCreatePbufferSurface");
    load(DestroySurface, "eglDestroySurface");
    load(MakeCurrent, "eglMakeCurrent");
    load(GetError, "eglGetError");
  }

  // Mesa's surfaceless platform needs no window system and no /dev/dri; else the default display.
  std::string open_display() {
    const char* client = QueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);  // null without client extensions
    auto platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(GetProcAddress("eglGetPlatformDisplayEXT"));
    EGLint major = 0, minor = 0;
    if (client && std::strstr(client, "EGL_MESA_platform_surfaceless") && platform_display) {
      display = platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
      if (display != EGL_NO_DISPLAY && Initialize(display, &major, &minor)) return "surfaceless";
    }
    display = GetDisplay(EGL_DEFAULT_DISPLAY);
    if (display == EGL_NO_DISPLAY) throw Unavailable(egl_error("eglGetDisplay", GetError()));
    if (!Initialize(display, &major, &minor)) {
      const EGLint e = GetError();
      display = EGL_NO_DISPLAY;
      throw Unavailable(egl_error("eglInitialize", e));
    }
    return "default display";
  }

  // An OpenGL 4.3 core context (compute shaders), current on this thread.
  void make_context(bool& pbuffer) {
    if (!BindAPI(EGL_OPENGL_API)) throw Unavailable(egl_error("eglBindAPI(EGL_OPENGL_API)", GetError()));
    const char* ext = QueryString(display, EGL_EXTENSIONS);
    const bool surfaceless = ext && std::strstr(ext, "EGL_KHR_surfaceless_context");
    pbuffer = !surfaceless;
    // Without a surface type the default is window surfaces, which the surfaceless platform has none of.
    const EGLint config_attribs[] = {EGL_SURFACE_TYPE, surfaceless ? 0 : EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE,
                                     EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint configs = 0;
    if (!ChooseConfig(display, config_attribs, &config, 1, &configs) || configs < 1)
      throw Unavailable("no EGL configuration renders OpenGL");
    const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 3,
                                      EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    context = CreateContext(display, config, EGL_NO_CONTEXT, context_attribs);
    if (context == EGL_NO_CONTEXT) throw Unavailable(egl_error("an OpenGL 4.3 core context (eglCreateContext)", GetError()));
    if (pbuffer) {
      const EGLint size[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
      surface = CreatePbufferSurface(display, config, size);
      if (surface == EGL_NO_SURFACE) throw Unavailable(egl_error("eglCreatePbufferSurface", GetError()));
    }
    if (!MakeCurrent(display, surface, surface, context)) throw Unavailable(egl_error("eglMakeCurrent", GetError()));
  }

  template <typename F>
  void load_gl(F& f, const char* name) {
    f = reinterpret_cast<F>(GetProcAddress(name));
    if (!f) throw Unavailable(std::string("the OpenGL context lacks ") + name);
  }
};

Context::Context() : egl_(std::make_unique<Egl>()) {
  egl_->open();
  info_.platform = egl_->open_display();
  bool pbuffer = false;
  egl_->make_context(pbuffer);
  if (pbuffer) info_.platform += ", pbuffer";
  Functions& f = functions_;
  egl_->load_gl(f.GetString, "glGetString");
  egl_->load_gl(f.GetError, "glGetError");
  egl_->load_gl(f.GetIntegerv, "glGetIntegerv");
  egl_->load_gl(f.Finish, "glFinish");
  egl_->load_gl(f.GenQueries, "glGenQueries");
  egl_->load_gl(f.DeleteQueries, "glDeleteQueries");
  egl_->load_gl(f.QueryCounter, "glQueryCounter");
  egl_->load_gl(f.GetQueryObjectui64v, "glGetQueryObjectui64v");
  egl_->load_gl(f.BindBuffer, "glBindBuffer");
  egl_->load_gl(f.BufferSubData, "glBufferSubData");
  egl_->load_gl(f.GetBufferSubData, "glGetBufferSubData");
  egl_->load_gl(f.MemoryBarrier, "glMemoryBarrier");
  auto text = [&](GLenum name) {
    const GLubyte* s = f.GetString(name);
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string();
  };
  info_.renderer = text(GL_RENDERER);
  info_.version = text(GL_VERSION);
  info_.vendor = text(GL_VENDOR);
  for (const char* software : {"llvmpipe", "softpipe", "swrast"})
    if (info_.renderer.rfind(software, 0) == 0) info_.software = true;
  info_.available = true;
}

Context::~Context() = default;

void Context::check(const char* doing) const {
  const GLenum e = functions_.GetError();
  if (e == GL_NO_ERROR) return;
  while (functions_.GetError() != GL_NO_ERROR) {
  }
  char buf[32];
  std::snprintf(buf, sizeof buf, "0x%04x", e);
  throw std::runtime_error(std::string("OpenGL error ") + buf + " while " + doing);
}

std::shared_ptr<Context> shared_context() {
  static std::mutex mutex;
  // Never destroyed: the driver's exit handlers, registered when libEGL loads it, may run before
  // static destructors, and tearing a context down after them crashes. The process exit frees it.
  static auto* context = new std::shared_ptr<Context>();
  static std::string failure;
  std::lock_guard<std::mutex> lock(mutex);
  if (*context) return *context;
  if (!failure.empty()) throw Unavailable(failure);
  try {
    context->reset(new Context());
  } catch (const Unavailable& e) {
    failure = e.what();
    throw;
  }
  return *context;
}

DeviceInfo probe() {
  try {
    return shared_context()->info();
  } catch (const Unavailable& e) {
    DeviceInfo none;
    none.reason = e.what();
    return none;
  }
}

std::string summary(const DeviceInfo& info) {
  if (!info.available) return info.reason;
  return info.renderer + ", OpenGL " + info.version + " (EGL " + info.platform + ")";
}

}  // namespace sdb::gl
