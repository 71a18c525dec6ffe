// SPDX-License-Identifier: MIT
// EGL headless context: surfaceless Mesa platform first (llvmpipe on CI and
// any Mesa driver), then the EGL device platform (NVIDIA without a display).
#include "terrasprite/gl/gl_context.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>
#include <fmt/format.h>

#include <stdexcept>
#include <vector>

#include "terrasprite/common/error.h"

namespace terrasprite {

struct GlContext::Impl {
  // An EGL context of ours, or an adopted one (external.make_current set).
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  EGLConfig config = nullptr;  // EGL_NO_CONFIG_KHR when the display allows it
  bool owns_display = true;    // a shared context leaves the display to its parent
  External external;
};

namespace {

bool has_client_ext(const char* name) {
  const char* exts = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  return exts && epoxy_extension_in_string(exts, name);
}

const EGLint kContextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                  4,
                                  EGL_CONTEXT_MINOR_VERSION,
                                  5,
                                  EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                  EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                  EGL_NONE};

EGLContext try_context(EGLDisplay dpy, EGLConfig& chosen) {
  EGLint major = 0, minor = 0;
  if (!eglInitialize(dpy, &major, &minor)) return EGL_NO_CONTEXT;
  if (!eglBindAPI(EGL_OPENGL_API)) return EGL_NO_CONTEXT;
  EGLConfig config = nullptr;
  EGLint count = 0;
  const EGLint config_attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, 0,
                                   EGL_NONE};
  bool no_config = epoxy_has_egl_extension(dpy, "EGL_KHR_no_config_context") ||
                   epoxy_has_egl_extension(dpy, "EGL_MESA_configless_context");
  if (!no_config && (!eglChooseConfig(dpy, config_attribs, &config, 1, &count) || count < 1))
    return EGL_NO_CONTEXT;
  chosen = no_config ? EGL_NO_CONFIG_KHR : config;
  EGLContext ctx = eglCreateContext(dpy, chosen, EGL_NO_CONTEXT, kContextAttribs);
  if (ctx == EGL_NO_CONTEXT) return EGL_NO_CONTEXT;
  if (!eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
    eglDestroyContext(dpy, ctx);
    return EGL_NO_CONTEXT;
  }
  return ctx;
}

}  // namespace

GlContext::GlContext() : impl_(std::make_unique<Impl>()) {
  std::vector<EGLDisplay> candidates;
  if (has_client_ext("EGL_MESA_platform_surfaceless"))
    candidates.push_back(
        eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr));
  if (has_client_ext("EGL_EXT_platform_device")) {
    EGLDeviceEXT devices[8];
    EGLint n = 0;
    if (eglQueryDevicesEXT(8, devices, &n))
      for (EGLint i = 0; i < n; ++i)
        candidates.push_back(
            eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr));
  }
  for (EGLDisplay dpy : candidates) {
    if (dpy == EGL_NO_DISPLAY) continue;
    EGLContext ctx = try_context(dpy, impl_->config);
    if (ctx != EGL_NO_CONTEXT) {
      impl_->display = dpy;
      impl_->context = ctx;
      if (epoxy_gl_version() < 45) break;
      return;
    }
    eglTerminate(dpy);
  }
  if (impl_->context != EGL_NO_CONTEXT) {
    eglMakeCurrent(impl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(impl_->display, impl_->context);
    eglTerminate(impl_->display);
  }
  throw DeviceError(
      "no usable GL device: could not create an OpenGL 4.5 core context through EGL (surfaceless "
      "or device platform)");
}

GlContext::GlContext(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

GlContext::~GlContext() {
  if (impl_->external.make_current) {
    if (impl_->external.destroy) impl_->external.destroy();
    return;
  }
  if (eglGetCurrentContext() == impl_->context)
    eglMakeCurrent(impl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(impl_->display, impl_->context);
  if (impl_->owns_display) eglTerminate(impl_->display);
}

std::unique_ptr<GlContext> GlContext::adopt(External external) {
  if (!external.make_current) throw std::logic_error("GlContext::adopt: make_current is required");
  if (epoxy_gl_version() < 45)
    throw DeviceError(
        fmt::format("no usable GL device: the window's context is OpenGL {}.{}, "
                    "4.5 core is needed",
                    epoxy_gl_version() / 10, epoxy_gl_version() % 10));
  auto impl = std::make_unique<Impl>();
  impl->external = std::move(external);
  return std::unique_ptr<GlContext>(new GlContext(std::move(impl)));
}

std::unique_ptr<GlContext> GlContext::create_shared() const {
  if (impl_->external.make_current) {
    if (!impl_->external.create_shared)
      throw DeviceError("no usable GL device: this window's context offers no shared context");
    return impl_->external.create_shared();
  }
  EGLContext ctx = eglCreateContext(impl_->display, impl_->config, impl_->context, kContextAttribs);
  if (ctx == EGL_NO_CONTEXT)
    throw DeviceError(
        fmt::format("no usable GL device: EGL could not create a shared context "
                    "(error 0x{:x})",
                    eglGetError()));
  auto impl = std::make_unique<Impl>();
  impl->display = impl_->display;
  impl->context = ctx;
  impl->config = impl_->config;
  impl->owns_display = false;
  return std::unique_ptr<GlContext>(new GlContext(std::move(impl)));
}

void GlContext::release_current() {
  if (impl_->external.make_current) {
    if (impl_->external.release_current) impl_->external.release_current();
    return;
  }
  eglMakeCurrent(impl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
}

std::string GlContext::renderer() const {
  const GLubyte* r = glGetString(GL_RENDERER);
  return r ? reinterpret_cast<const char*>(r) : "unknown";
}

void GlContext::make_current() {
  if (impl_->external.make_current) {
    impl_->external.make_current();
    return;
  }
  if (!eglMakeCurrent(impl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, impl_->context))
    throw DeviceError(
        fmt::format("no usable GL device: eglMakeCurrent failed (error 0x{:x})", eglGetError()));
}

}  // namespace terrasprite
