// SPDX-License-Identifier: MIT
// Whether a camera above a double-sided LOD level sees any of its back faces:
// the level drawn from views above it with back faces marked (gl_model_impl.h).
#include <algorithm>
#include <cmath>
#include <glm/gtc/type_ptr.hpp>

#include "gl/render_target.h"
#include "objects/gl_model_impl.h"

namespace terrasprite {
namespace {

constexpr int kSide = 64;  // pixels: the level fills about half of it
// A back face peeking past a front one's silhouette by a pixel is no opening.
constexpr double kMaxBackFraction = 0.005;  // of the pixels the level covers

// Pixels the level covers (not the sky's) and of those the back faces'.
std::pair<std::size_t, std::size_t> covered_and_back(const Image& marked, const Image& sky) {
  std::size_t covered = 0, back = 0;
  for (std::size_t i = 0; i < marked.rgba.size(); i += 4) {
    const std::uint8_t *p = &marked.rgba[i], *s = &sky.rgba[i];
    if (p[0] == s[0] && p[1] == s[1] && p[2] == s[2]) continue;
    ++covered;
    back += p[0] == 255 && p[1] == 0 && p[2] == 0;
  }
  return {covered, back};
}

}  // namespace

std::vector<double> GlModel::Impl::find_back_faces_hidden_above() {
  std::vector<double> out(chain.size(), INFINITY);
  auto double_sided = [&](const LodLevel& lv) {
    for (const MeshPart& part : lv.parts)
      if (model.materials[part.material].double_sided) return true;
    return false;
  };
  if (std::none_of(chain.begin(), chain.end(), double_sided)) return out;
  // Above the top the camera is outside every closed part: a back face can
  // show only through an opening facing up (a cup) or as a face wound the
  // wrong way.
  const double top = model.bounds_max.z;
  const glm::dvec3 centre(model.center());
  const double r = std::max(model.bounding_radius(), 1e-6);

  GLint saved_fbo = 0, saved_viewport[4];
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &saved_fbo);
  glGetIntegerv(GL_VIEWPORT, saved_viewport);
  gl::RenderTarget target(kSide, kSide);
  target.bind_and_clear();
  const Image sky = target.read_color();
  // One program for every level: llvmpipe compiles a program's shaders at
  // its first draw.
  const gl::Program mark = objects::make_back_face_mark_program();
  const GLuint p = mark.id();
  glUseProgram(p);
  const ObjectInstance identity;
  for (std::size_t level = 0; level < chain.size(); ++level) {
    if (!double_sided(chain[level])) continue;
    upload_instances(std::span(&identity, 1), levels[level].vao.id());
    bool hidden = true;
    // Just above the top, above it, and high up; from over the footprint and
    // beside it; two azimuths each, four in all per height.
    for (double dz : {0.02, 0.4, 1.5})
      for (double dist : {0.5, 2.0})
        for (int k = 0; k < 2 && hidden; ++k) {
          const double a = glm::radians(15.0 + 180.0 * k + 45.0 * dist);
          const glm::dvec3 eye(centre.x + dist * r * std::cos(a), centre.y + dist * r * std::sin(a),
                               top + dz * r);
          Camera cam = Camera::look_at(eye, centre, 60.0, 1.0);
          cam.near_m = 0.01 * r;
          cam.far_m = 20.0 * r;
          target.bind_and_clear();
          const glm::mat4 vp(gl::view_projection_reversed_z(cam));
          glUniformMatrix4fv(glGetUniformLocation(p, "u_vp"), 1, GL_FALSE, glm::value_ptr(vp));
          draw_level_parts(int(level), p, 1);
          const auto [covered, back] = covered_and_back(target.read_color(), sky);
          hidden = double(back) <= kMaxBackFraction * double(covered);
        }
    if (hidden) out[level] = top;
  }
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(saved_fbo));
  glViewport(saved_viewport[0], saved_viewport[1], saved_viewport[2], saved_viewport[3]);
  return out;
}

}  // namespace terrasprite
