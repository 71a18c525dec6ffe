// SPDX-License-Identifier: MIT
// A headless OpenGL 4.5 core context through EGL.
#pragma once
#include <memory>
#include <string>

namespace terrasprite {

/// Creates an OpenGL 4.5 core context on EGL's surfaceless Mesa platform
/// (llvmpipe or a GPU driver), falling back to the EGL device platform, and
/// makes it current on the calling thread. All GL objects must be destroyed
/// before the context. Throws DeviceError with one line when no GL 4.5 core
/// context can be had.
class GlContext {
 public:
  GlContext();
  ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  /// GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
  std::string renderer() const;
  /// Makes the context current on the calling thread again.
  void make_current();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace terrasprite
