// SPDX-License-Identifier: MIT
// The OpenGL 4.5 core context the GL renderers draw with: a headless EGL one,
// a window's (adopted), and second contexts sharing objects with either.
#pragma once
#include <functional>
#include <memory>
#include <string>

namespace terrasprite {

/// A GL context. Renderers need only that some GlContext is current on the
/// thread that calls them; they never ask which kind. All GL objects made in
/// a context (or one sharing with it) must be destroyed before it.
class GlContext {
 public:
  /// Creates an OpenGL 4.5 core context on EGL's surfaceless Mesa platform
  /// (llvmpipe or a GPU driver), falling back to the EGL device platform, and
  /// makes it current on the calling thread. Throws DeviceError with one line
  /// when no GL 4.5 core context can be had.
  GlContext();
  ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  /// How to drive a context created elsewhere (a GLFW window's).
  struct External {
    std::function<void()> make_current;     ///< binds it to the calling thread (required)
    std::function<void()> release_current;  ///< unbinds it (may be empty)
    /// Creates a context sharing its objects (e.g. a hidden GLFW window with
    /// `share` set), wrapped with adopt(); may be empty when none is needed.
    std::function<std::unique_ptr<GlContext>()> create_shared;
    std::function<void()> destroy;  ///< called by the destructor (may be empty: the caller owns it)
  };
  /// Wraps a context created elsewhere; it must be current on the calling
  /// thread already. Throws DeviceError when the current context is not GL 4.5 core.
  static std::unique_ptr<GlContext> adopt(External external);

  /// A second context sharing textures, buffers and programs with this one,
  /// for work on another thread (asynchronous keyframes, background
  /// rendering). It is not current anywhere: call make_current() on the thread
  /// that uses it; each context is current on one thread at a time. Throws
  /// DeviceError when it cannot be made. Must be destroyed before this one.
  std::unique_ptr<GlContext> create_shared() const;

  /// GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"; the context must be current.
  std::string renderer() const;
  /// Makes the context current on the calling thread.
  void make_current();
  /// Unbinds it from the calling thread (so another thread may take it).
  void release_current();

 private:
  struct Impl;
  explicit GlContext(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace terrasprite
