// SPDX-License-Identifier: MIT
// EGL headless context: surfaceless Mesa platform first (llvmpipe on CI and
// any Mesa driver), then the EGL device platform (NVIDIA without a display).
#include "terrasprite/gl_context.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>
#include <fmt/format.h>

#include <vector>

#include "terrasprite/error.h"

namespace terrasprite {

struct GlContext::Impl {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
};

namespace {

bool has_client_ext(const char* name) {
  const char* exts = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  return exts && epoxy_extension_in_string(exts, name);
}

EGLContext try_context(EGLDisplay dpy) {
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
  const EGLint ctx_attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                4,
                                EGL_CONTEXT_MINOR_VERSION,
                                5,
                                EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                EGL_NONE};
  EGLContext ctx =
      eglCreateContext(dpy, no_config ? EGL_NO_CONFIG_KHR : config, EGL_NO_CONTEXT, ctx_attribs);
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
    EGLContext ctx = try_context(dpy);
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

GlContext::~GlContext() {
  eglMakeCurrent(impl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(impl_->display, impl_->context);
  eglTerminate(impl_->display);
}

std::string GlContext::renderer() const {
  const GLubyte* r = glGetString(GL_RENDERER);
  return r ? reinterpret_cast<const char*>(r) : "unknown";
}

void GlContext::make_current() {
  eglMakeCurrent(impl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, impl_->context);
}

}  // namespace terrasprite
