// SPDX-License-Identifier: MIT
#include <stdexcept>
#include <vector>

#include "gl/gl_objects.h"

namespace terrasprite::gl {
namespace {

GLuint compile(GLenum type, const std::string& src) {
  GLuint s = glCreateShader(type);
  const char* p = src.c_str();
  glShaderSource(s, 1, &p, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    GLint len = 0;
    glGetShaderiv(s, GL_INFO_LOG_LENGTH, &len);
    std::vector<char> log(len + 1, 0);
    glGetShaderInfoLog(s, len, nullptr, log.data());
    glDeleteShader(s);
    throw std::logic_error(std::string("shader compile failed: ") + log.data());
  }
  return s;
}

}  // namespace

Program link_program(const std::string& vertex_src, const std::string& fragment_src) {
  Program prog;
  GLuint vs = compile(GL_VERTEX_SHADER, vertex_src);
  GLuint fs = compile(GL_FRAGMENT_SHADER, fragment_src);
  glAttachShader(prog.id(), vs);
  glAttachShader(prog.id(), fs);
  glLinkProgram(prog.id());
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(prog.id(), GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint len = 0;
    glGetProgramiv(prog.id(), GL_INFO_LOG_LENGTH, &len);
    std::vector<char> log(len + 1, 0);
    glGetProgramInfoLog(prog.id(), len, nullptr, log.data());
    throw std::logic_error(std::string("program link failed: ") + log.data());
  }
  return prog;
}

}  // namespace terrasprite::gl
