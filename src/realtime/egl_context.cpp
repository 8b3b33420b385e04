#include "realtime/egl_context.h"

#include <dlfcn.h>
#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <cstdlib>
#include <cstring>
#include <utility>
#include <vector>

namespace relight {

namespace {

bool has_extension(EGLDisplay display, const char* name) {
  return epoxy_has_egl_extension(display, name);
}

// The displays to try, best first: the devices (a GPU before a software
// one), then Mesa's surfaceless platform, then the default display.
std::vector<EGLDisplay> candidate_displays() {
  std::vector<EGLDisplay> hardware, software;
  if (has_extension(EGL_NO_DISPLAY, "EGL_EXT_platform_device") &&
      has_extension(EGL_NO_DISPLAY, "EGL_EXT_device_enumeration")) {
    EGLDeviceEXT devices[16];
    EGLint n = 0;
    if (eglQueryDevicesEXT(16, devices, &n)) {
      for (EGLint i = 0; i < n; ++i) {
        const char* ext = eglQueryDeviceStringEXT(devices[i], EGL_EXTENSIONS);
        const bool is_software = ext && std::strstr(ext, "EGL_MESA_device_software");
        EGLDisplay d = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        if (d != EGL_NO_DISPLAY) (is_software ? software : hardware).push_back(d);
      }
    }
  }
  std::vector<EGLDisplay> all = hardware;
  if (has_extension(EGL_NO_DISPLAY, "EGL_MESA_platform_surfaceless")) {
    EGLDisplay d = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (d != EGL_NO_DISPLAY) all.push_back(d);
  }
  all.insert(all.end(), software.begin(), software.end());
  EGLDisplay d = eglGetDisplay(EGL_DEFAULT_DISPLAY);
  if (d != EGL_NO_DISPLAY) all.push_back(d);
  return all;
}

// An OpenGL core context on `display`, without a surface: 4.3 (compute
// shaders) where the driver has it, else 3.3. A driver may give exactly the
// version asked for (NVIDIA's does), so the newer is asked for first.
EGLContext create_context(EGLDisplay display) {
  if (!eglBindAPI(EGL_OPENGL_API)) return EGL_NO_CONTEXT;
  EGLConfig config = nullptr;
  const EGLint config_attributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
  EGLint count = 0;
  if (!eglChooseConfig(display, config_attributes, &config, 1, &count) || count == 0) {
    if (!has_extension(display, "EGL_KHR_no_config_context")) return EGL_NO_CONTEXT;
    config = EGL_NO_CONFIG_KHR;
  }
  for (const auto& [major, minor] : {std::pair{4, 3}, std::pair{3, 3}}) {
    const EGLint context_attributes[] = {
        EGL_CONTEXT_MAJOR_VERSION,           major,   EGL_CONTEXT_MINOR_VERSION, minor, EGL_CONTEXT_OPENGL_PROFILE_MASK,
        EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    const EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, context_attributes);
    if (context != EGL_NO_CONTEXT) return context;
  }
  return EGL_NO_CONTEXT;
}

}  // namespace

std::unique_ptr<HeadlessContext> HeadlessContext::open(std::string& why) {
  if (const char* env = std::getenv("RELIGHT_GL"); env && std::strcmp(env, "off") == 0) {
    why = "RELIGHT_GL=off";
    return nullptr;
  }
  // libepoxy loads libEGL on first use and aborts if it cannot: look first.
  if (!dlopen("libEGL.so.1", RTLD_LAZY | RTLD_GLOBAL)) {
    why = "libEGL.so.1 not found";
    return nullptr;
  }
  why = "no EGL display could be opened";
  for (EGLDisplay display : candidate_displays()) {
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor)) continue;
    if (!has_extension(display, "EGL_KHR_surfaceless_context")) {
      why = "the EGL display cannot make a context current without a surface";
      continue;
    }
    EGLContext context = create_context(display);
    if (context == EGL_NO_CONTEXT) {
      why = "no OpenGL 3.3 core context on the EGL display";
      continue;
    }
    auto result = std::unique_ptr<HeadlessContext>(new HeadlessContext());
    result->display_ = display;
    result->context_ = context;
    {
      Current current(*result);
      if (epoxy_gl_version() < 33) {
        why = "OpenGL " + std::to_string(epoxy_gl_version() / 10) + "." + std::to_string(epoxy_gl_version() % 10) +
              " is below 3.3";
        continue;  // the destructor releases the context
      }
      result->renderer_ = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
      result->version_ = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    }
    why.clear();
    return result;
  }
  return nullptr;
}

bool HeadlessContext::software() const {
  return renderer_.find("llvmpipe") != std::string::npos || renderer_.find("softpipe") != std::string::npos;
}

HeadlessContext::~HeadlessContext() {
  if (context_) eglDestroyContext(display_, context_);
}

HeadlessContext::Current::Current(HeadlessContext& context) : context_(context), lock_(context.mutex_) {
  eglMakeCurrent(context_.display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_.context_);
}

HeadlessContext::Current::~Current() {
  eglMakeCurrent(context_.display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
}

}  // namespace relight
