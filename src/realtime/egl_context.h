// A headless OpenGL core context (4.3 where the driver has it, at least 3.3)
// through EGL: the GPU's driver where
// there is one, Mesa's software rasteriser (llvmpipe) elsewhere; nothing
// where no EGL display can be opened. A context is current on one thread at
// a time: Current makes it current for a scope, on any thread.
#pragma once

#include <memory>
#include <mutex>
#include <string>

namespace relight {

class HeadlessContext {
 public:
  // nullptr, with the reason in `why`, where no EGL display or no OpenGL 3.3
  // core context can be had. RELIGHT_GL=off in the environment acts as if
  // there were none (to try the fallbacks).
  static std::unique_ptr<HeadlessContext> open(std::string& why);
  ~HeadlessContext();
  HeadlessContext(const HeadlessContext&) = delete;
  HeadlessContext& operator=(const HeadlessContext&) = delete;

  // GL_RENDERER and GL_VERSION.
  const std::string& renderer() const { return renderer_; }
  const std::string& version() const { return version_; }
  // Whether the renderer is Mesa's software rasteriser (llvmpipe, softpipe)
  // rather than a GPU's driver.
  bool software() const;

  // Makes the context current on this thread for its lifetime (one thread
  // at a time: others wait).
  class Current {
   public:
    explicit Current(HeadlessContext& context);
    ~Current();
    Current(const Current&) = delete;
    Current& operator=(const Current&) = delete;

   private:
    HeadlessContext& context_;
    std::lock_guard<std::mutex> lock_;
  };

 private:
  HeadlessContext() = default;
  void* display_ = nullptr;  // EGLDisplay
  void* context_ = nullptr;  // EGLContext
  std::string renderer_, version_;
  std::mutex mutex_;
};

}  // namespace relight
