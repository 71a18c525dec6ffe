// SPDX-License-Identifier: MIT
// Relief-texture impostor: Oliveira, Bishop, McAllister, "Relief Texture
// Mapping" (SIGGRAPH 2000), drawn per pixel as in Policarpo, Oliveira, Comba,
// "Real-Time Relief Mapping on Arbitrary Polygonal Surfaces" (I3D 2005):
// the object's bounding box, each face a colour + depth image of the object
// seen orthographically through it; each fragment marches its view ray
// (linear search, then binary refinement) and writes the hit's true depth.
//
// A ray point counts as solid when it lies behind the surface recorded by
// every face the ray can see (up to three), not only the face it entered.
// (Also requiring it to lie before the opposite faces' surfaces carves
// concavities better on closed objects, but breaks open shells: from below,
// a car body's depth map sees the inside of its roof.) The hit is the
// nearest solid point. Faces that disagree are resolved at the hit: its
// colour and normal come from a visible face whose recorded surface passes
// within 1.5 texels of it, the one that saw the surface most head-on; when no
// face is that close, from the face whose surface is nearest.
#include <fmt/format.h>

#include <algorithm>
#include <glm/gtc/type_ptr.hpp>

#include "gl/render_target.h"
#include "objects/capture.h"
#include "objects/gl_model_impl.h"
#include "objects/impostor_cache.h"

namespace terrasprite {
namespace objects {
namespace {

const char* kReliefVertex = R"(
uniform vec3 u_lo, u_hi;  // the box, model metres
uniform mat4 u_vp;
uniform vec3 u_eye;       // camera, world metres
out vec3 v_local;
flat out vec3 v_eye_local;
flat out vec4 v_ph;
flat out float v_scale;
const int kCorner[36] = int[36](0,1,3, 0,3,2, 4,6,7, 4,7,5, 0,4,5, 0,5,1, 2,3,7, 2,7,6, 0,2,6, 0,6,4, 1,5,7, 1,7,3);
void main() {
  int c = kCorner[gl_VertexID];
  vec3 f = vec3(c & 1, (c >> 1) & 1, (c >> 2) & 1);
  v_local = mix(u_lo, u_hi, f);
  v_eye_local = world_to_instance(u_eye);
  v_ph = i_pos_heading;
  v_scale = i_scale.x;
  gl_Position = u_vp * vec4(instance_to_world(v_local), 1.0);
}
)";

const char* kReliefFragment = R"(
uniform sampler2DArray u_albedo;
uniform sampler2DArray u_geometry;
uniform vec3 u_lo, u_hi;
uniform mat4 u_vp;
uniform int u_res;
uniform int u_steps;
in vec3 v_local;
flat in vec3 v_eye_local;
flat in vec4 v_ph;
flat in float v_scale;
out vec4 o_color;

vec4 fetch_geometry(vec3 q, int face) {
  int a = face >> 1;
  vec2 st = vec2(q[(a + 1) % 3], q[(a + 2) % 3]);
  ivec2 t = clamp(ivec2(st * float(u_res)), ivec2(0), ivec2(u_res - 1));
  return texelFetch(u_geometry, ivec3(t, face), 0);
}
// Where face `face` sees the surface along q's line, in q's coordinate on its axis.
float surface(vec3 q, int face) {
  float d = fetch_geometry(q, face).a;
  return (face & 1) == 0 ? 1.0 - d : d;
}
vec3 g_dir;  // the ray's direction (signs select the faces it can see)
bool solid(vec3 q) {
  const float eps = 1e-4;
  for (int a = 0; a < 3; ++a) {
    if (g_dir[a] <= 0.0 && q[a] > surface(q, 2 * a) + eps) return false;      // before the + face's surface
    if (g_dir[a] >= 0.0 && q[a] < surface(q, 2 * a + 1) - eps) return false;  // before the - face's surface
  }
  return true;
}
void main() {
  vec3 ext = u_hi - u_lo;
  vec3 o = (v_eye_local - u_lo) / ext;
  vec3 d = (v_local - v_eye_local) / ext;
  g_dir = d;
  // Slabs of the unit box.
  vec3 inv = 1.0 / d;
  vec3 t0 = (vec3(0.0) - o) * inv, t1 = (vec3(1.0) - o) * inv;
  vec3 tn = min(t0, t1), tf = max(t0, t1);
  float t_in = max(max(max(tn.x, tn.y), tn.z), 0.0);
  float t_out = min(min(tf.x, tf.y), tf.z);
  // Only the fragment on the far side of the box marches (front and back both rasterise).
  if (t_out > 1.001 || t_in >= t_out) discard;
  float step = (t_out - t_in) / float(u_steps);
  float lo = t_in, hi = -1.0;
  if (solid(o + t_in * d)) hi = t_in;
  for (int i = 1; i <= u_steps && hi < 0.0; ++i) {
    float t = t_in + float(i) * step;
    if (solid(o + t * d)) hi = t; else lo = t;
  }
  if (hi < 0.0) discard;
  for (int i = 0; i < 8 && hi > lo; ++i) {
    float mid = 0.5 * (lo + hi);
    if (solid(o + mid * d)) hi = mid; else lo = mid;
  }
  vec3 q = o + hi * d;
  // Colour from a visible face that recorded a surface at the hit (within
  // 1.5 texels); among those, the one that saw it most head-on (its stored
  // normal facing it: grazing texels at a capture's silhouette carry poor
  // normals and colours). No face within the tolerance: the nearest surface.
  vec3 dir = normalize(d * ext);
  int best = -1, nearest = 0;
  float best_facing = -2.0, nearest_err = 1e9;
  for (int face = 0; face < 6; ++face) {
    int a = face >> 1;
    float sign = (face & 1) == 0 ? 1.0 : -1.0;
    if (sign * dir[a] >= 0.0) continue;  // the ray cannot see this face
    vec4 g = fetch_geometry(q, face);
    if (g.a > 0.9999) continue;  // no surface on this line
    float err = abs(q[a] - ((face & 1) == 0 ? 1.0 - g.a : g.a)) * ext[a];
    if (err < nearest_err) { nearest = face; nearest_err = err; }
    float facing = sign * g[a];  // stored normal towards this face's viewer
    if (err <= 1.5 * ext[a] / float(u_res) && facing > best_facing) { best = face; best_facing = facing; }
  }
  if (best < 0) best = nearest;
  int a = best >> 1;
  ivec2 t = clamp(ivec2(vec2(q[(a + 1) % 3], q[(a + 2) % 3]) * float(u_res)), ivec2(0), ivec2(u_res - 1));
  vec3 albedo = texelFetch(u_albedo, ivec3(t, best), 0).rgb;
  vec3 n = texelFetch(u_geometry, ivec3(t, best), 0).rgb;
  float c = cos(v_ph.w), s = sin(v_ph.w);
  mat3 rot = mat3(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0);  // heading_rotate as a matrix
  vec3 world = v_ph.xyz + rot * ((u_lo + q * ext) * v_scale);
  vec4 clip = u_vp * vec4(world, 1.0);
  gl_FragDepth = clip.z / clip.w;
  o_color = vec4(sun_lit(albedo, rot * n), 1.0);
}
)";

// Face f: axis a = f / 2; even faces look from the + side. Texel (s, t) spans
// axes (a+1)%3 and (a+2)%3; depth runs from the face into the box.
glm::mat4 face_capture(int face, glm::vec3 lo, glm::vec3 hi) {
  const int a = face / 2, u = (a + 1) % 3, v = (a + 2) % 3;
  const glm::vec3 ext = hi - lo;
  glm::vec4 rs(0.f), rt(0.f), rd(0.f);
  rs[u] = 2.f / ext[u], rs.w = -2.f * lo[u] / ext[u] - 1.f;
  rt[v] = 2.f / ext[v], rt.w = -2.f * lo[v] / ext[v] - 1.f;
  if (face % 2 == 0)
    rd[a] = -1.f / ext[a], rd.w = hi[a] / ext[a];
  else
    rd[a] = 1.f / ext[a], rd.w = -lo[a] / ext[a];
  return from_rows(rs, rt, rd);
}

}  // namespace

gl::Program make_relief_program() {
  const std::string head = std::string("#version 450 core\n") + kObjectGlsl;
  return gl::link_program(head + kReliefVertex,
                          std::string("#version 450 core\n") + kSunGlsl + kReliefFragment);
}

/// The box the impostor spans: the model's bounds grown by 0.5% of the diagonal.
void relief_box(const Model& m, glm::vec3& lo, glm::vec3& hi) {
  const float margin = 0.005f * glm::length(m.bounds_max - m.bounds_min);
  lo = m.bounds_min - margin;
  hi = m.bounds_max + margin;
}

}  // namespace objects

objects::ReliefImpostor& GlModel::Impl::relief_impostor(int res) {
  auto it = relief.find(res);
  if (it != relief.end()) return it->second;
  objects::ReliefImpostor& r = relief[res];
  r.resolution = res;
  glTextureStorage3D(r.albedo.id(), 1, GL_RGBA8, res, res, 6);
  glTextureStorage3D(r.geometry.id(), 1, GL_RGBA16F, res, res, 6);
  r.bytes = std::size_t(res) * res * 6 * (4 + 8);
  const std::string what = fmt::format("relief-{}", res);
  const objects::TextureLevel albedo{r.albedo.id(), GL_TEXTURE_2D_ARRAY, res, res, 6,
                                     GL_RGBA,       GL_UNSIGNED_BYTE,    4};
  const objects::TextureLevel geometry{r.geometry.id(), GL_TEXTURE_2D_ARRAY, res, res, 6,
                                       GL_RGBA,         GL_HALF_FLOAT,       8};
  if (objects::load_impostor(cache, what, {albedo, geometry})) return r;
  const double t0 = objects::ms_now();
  gl::Texture depth(GL_TEXTURE_2D);
  glTextureStorage2D(depth.id(), 1, GL_DEPTH_COMPONENT32F, res, res);
  gl::Framebuffer fbo;
  glm::vec3 lo, hi;
  objects::relief_box(model, lo, hi);
  objects::GlStateGuard guard;
  const GLenum bufs[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glNamedFramebufferDrawBuffers(fbo.id(), 2, bufs);
  glNamedFramebufferTexture(fbo.id(), GL_DEPTH_ATTACHMENT, depth.id(), 0);
  for (int face = 0; face < 6; ++face) {
    glNamedFramebufferTextureLayer(fbo.id(), GL_COLOR_ATTACHMENT0, r.albedo.id(), 0, face);
    glNamedFramebufferTextureLayer(fbo.id(), GL_COLOR_ATTACHMENT1, r.geometry.id(), 0, face);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
    glViewport(0, 0, res, res);
    const float clear_albedo[4] = {0, 0, 0, 0}, clear_geometry[4] = {0, 0, 1, 1}, far = 1.f;
    glClearNamedFramebufferfv(fbo.id(), GL_COLOR, 0, clear_albedo);
    glClearNamedFramebufferfv(fbo.id(), GL_COLOR, 1, clear_geometry);
    glClearNamedFramebufferfv(fbo.id(), GL_DEPTH, 0, &far);
    objects::capture_view(*this, objects::face_capture(face, lo, hi), false);
  }
  objects::store_impostor(cache, what, {albedo, geometry}, t0);
  return r;
}

void GlModel::Impl::draw_relief(const objects::ReliefImpostor& r, GLsizei count, GLuint first,
                                const Camera& camera) {
  const GLuint p = relief_program.id();
  glUseProgram(p);
  glm::vec3 lo, hi;
  objects::relief_box(model, lo, hi);
  const glm::mat4 vp(gl::view_projection_reversed_z(camera));
  glUniformMatrix4fv(glGetUniformLocation(p, "u_vp"), 1, GL_FALSE, glm::value_ptr(vp));
  glUniform3fv(glGetUniformLocation(p, "u_lo"), 1, glm::value_ptr(lo));
  glUniform3fv(glGetUniformLocation(p, "u_hi"), 1, glm::value_ptr(hi));
  glUniform3f(glGetUniformLocation(p, "u_eye"), float(camera.position.x), float(camera.position.y),
              float(camera.position.z));
  glUniform1i(glGetUniformLocation(p, "u_res"), r.resolution);
  // Linear steps across the box: half a step per texel, at most 48 (binary
  // refinement recovers the depth; features thinner than a step may be missed).
  glUniform1i(glGetUniformLocation(p, "u_steps"), std::clamp(r.resolution / 2, 16, 48));
  glUniform1i(glGetUniformLocation(p, "u_albedo"), 0);
  glUniform1i(glGetUniformLocation(p, "u_geometry"), 1);
  glBindTextureUnit(0, r.albedo.id());
  glBindTextureUnit(1, r.geometry.id());
  glBindVertexArray(instance_vao.id());
  glDrawArraysInstancedBaseInstance(GL_TRIANGLES, 0, 36, count, first);
}

}  // namespace terrasprite
