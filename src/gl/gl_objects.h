// SPDX-License-Identifier: MIT
// RAII owners for GL objects. Each owns one name, deletes it on destruction,
// and moves but never copies. A GlContext must be current.
#pragma once
#include <epoxy/gl.h>

#include <string>
#include <utility>

namespace terrasprite::gl {

template <typename Traits>
class Object {
 public:
  Object() : id_(Traits::create()) {}
  explicit Object(GLenum target) : id_(Traits::create(target)) {}
  ~Object() {
    if (id_) Traits::destroy(id_);
  }
  Object(Object&& o) noexcept : id_(std::exchange(o.id_, 0)) {}
  Object& operator=(Object&& o) noexcept {
    if (this != &o) {
      if (id_) Traits::destroy(id_);
      id_ = std::exchange(o.id_, 0);
    }
    return *this;
  }
  Object(const Object&) = delete;
  Object& operator=(const Object&) = delete;
  GLuint id() const { return id_; }

 private:
  GLuint id_ = 0;
};

struct BufferTraits {
  static GLuint create() {
    GLuint i;
    glCreateBuffers(1, &i);
    return i;
  }
  static void destroy(GLuint i) { glDeleteBuffers(1, &i); }
};
struct TextureTraits {
  static GLuint create(GLenum target) {
    GLuint i;
    glCreateTextures(target, 1, &i);
    return i;
  }
  static void destroy(GLuint i) { glDeleteTextures(1, &i); }
};
struct FramebufferTraits {
  static GLuint create() {
    GLuint i;
    glCreateFramebuffers(1, &i);
    return i;
  }
  static void destroy(GLuint i) { glDeleteFramebuffers(1, &i); }
};
struct RenderbufferTraits {
  static GLuint create() {
    GLuint i;
    glCreateRenderbuffers(1, &i);
    return i;
  }
  static void destroy(GLuint i) { glDeleteRenderbuffers(1, &i); }
};
struct VertexArrayTraits {
  static GLuint create() {
    GLuint i;
    glCreateVertexArrays(1, &i);
    return i;
  }
  static void destroy(GLuint i) { glDeleteVertexArrays(1, &i); }
};
struct QueryTraits {
  static GLuint create(GLenum target) {
    GLuint i;
    glCreateQueries(target, 1, &i);
    return i;
  }
  static void destroy(GLuint i) { glDeleteQueries(1, &i); }
};
struct ProgramTraits {
  static GLuint create() { return glCreateProgram(); }
  static void destroy(GLuint i) { glDeleteProgram(i); }
};

using Buffer = Object<BufferTraits>;
using Texture = Object<TextureTraits>;
using Framebuffer = Object<FramebufferTraits>;
using Renderbuffer = Object<RenderbufferTraits>;
using VertexArray = Object<VertexArrayTraits>;
using Query = Object<QueryTraits>;
using Program = Object<ProgramTraits>;

/// Compiles and links a vertex + fragment program. Shader sources are ours,
/// so a compile or link failure is a programmer error: throws std::logic_error
/// with GL's info log.
Program link_program(const std::string& vertex_src, const std::string& fragment_src);

}  // namespace terrasprite::gl
