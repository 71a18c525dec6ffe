// SPDX-License-Identifier: MIT
#include "viewer/frame_view.h"

#include <epoxy/gl.h>

#include "gl/gl_objects.h"
#include "terrasprite/camera/renderer.h"

namespace terrasprite::viewer {

namespace {

// A triangle covering the screen; v flipped for an uploaded image (row 0 at the top).
constexpr const char* kVertex = R"(#version 450 core
layout(location = 0) uniform bool flip;
out vec2 uv;
void main() {
  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
  uv = vec2(p.x, flip ? 1.0 - p.y : p.y);
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)";
constexpr const char* kFragment = R"(#version 450 core
in vec2 uv;
layout(binding = 0) uniform sampler2D image;
out vec4 color;
void main() { color = vec4(texture(image, uv).rgb, 1.0); }
)";

}  // namespace

struct FrameView::Impl {
  gl::Program program = gl::link_program(kVertex, kFragment);
  gl::VertexArray vao;
  gl::Texture texture{GL_TEXTURE_2D};  // uploads
  int width = 0, height = 0;
  unsigned shown = 0;  // the texture drawn: ours (uploaded, flipped) or the worker's
};

FrameView::FrameView() : impl_(std::make_unique<Impl>()) {}
FrameView::~FrameView() = default;

void FrameView::upload(const Image& color) {
  Impl& s = *impl_;
  if (color.width != s.width || color.height != s.height) {
    s.texture = gl::Texture(GL_TEXTURE_2D);
    glTextureStorage2D(s.texture.id(), 1, GL_RGBA8, color.width, color.height);
    glTextureParameteri(s.texture.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(s.texture.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(s.texture.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(s.texture.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    s.width = color.width;
    s.height = color.height;
  }
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTextureSubImage2D(s.texture.id(), 0, 0, 0, color.width, color.height, GL_RGBA, GL_UNSIGNED_BYTE,
                      color.rgba.data());
  s.shown = s.texture.id();
}

void FrameView::show(unsigned texture) {
  impl_->shown = texture;
}

void FrameView::draw(int width, int height) const {
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glClearColor(kSkyColor[0] / 255.f, kSkyColor[1] / 255.f, kSkyColor[2] / 255.f, 1.f);
  glClear(GL_COLOR_BUFFER_BIT);
  if (impl_->shown == 0) return;
  glUseProgram(impl_->program.id());
  glUniform1i(0, impl_->shown == impl_->texture.id());
  glBindTextureUnit(0, impl_->shown);
  glBindVertexArray(impl_->vao.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
}

}  // namespace terrasprite::viewer
