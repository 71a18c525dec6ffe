// SPDX-License-Identifier: MIT
// Octahedral impostor (R. Brucks, "Octahedral Impostors", 2018; as in Unreal
// Engine's ImpostorBaker): views x views orthographic views of the object
// from directions on the upper hemi-octahedron, one atlas of albedo +
// coverage and normal + 16-bit depth; drawn as a camera-facing quad. Each
// fragment marches its view ray through the intersection of the depth-map
// solids of the three views nearest the view direction (one view alone
// extrudes its surface into what the others see: ghosts), writes the hit's
// true depth, and takes colour and normal from the views that recorded a
// surface at the hit, blended by the views' barycentric weights. The views
// frame the sphere through the model's farthest vertex from its centre.
//
//   hemi-octahedral map: d (d.z >= 0) -> a = d.xy / (|x|+|y|+z),
//   grid (u, v) = (a.x + a.y, a.x - a.y) in [-1, 1]^2; frame (i, j) at
//   u = 2 i / (views - 1) - 1 (grid points include the horizon, whose
//   views are raised to 4 degrees: see oct_decode).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/type_ptr.hpp>

#include "gl/render_target.h"
#include "objects/capture.h"
#include "objects/gl_model_impl.h"
#include "objects/impostor_cache.h"

namespace terrasprite {
namespace objects {
namespace {

// A capture direction is the grid point's, raised to at least 4 degrees above
// the horizon. A flat part (a ground tile, a leaf card) seen exactly edge-on
// is in no view, and the intersection of the views' solids carves it out of
// every ray: the forest's ground tile vanished seen from the side. One
// constant for both sides: octahedral_glsl() hands it to the shaders.
constexpr float kMinSinElevation = 0.0698f;  // sin(4 degrees)

const char* kOctGlsl = R"(
vec3 oct_decode(vec2 g) {
  vec2 a = vec2(g.x + g.y, g.x - g.y) * 0.5;
  vec3 d = normalize(vec3(a, max(1.0 - abs(a.x) - abs(a.y), 0.0)));
  if (d.z < kMinSinElevation)
    d = vec3(normalize(d.xy) * sqrt(1.0 - kMinSinElevation * kMinSinElevation), kMinSinElevation);
  return d;
}
vec2 oct_encode(vec3 d) {
  d.z = max(d.z, 0.0);
  d /= abs(d.x) + abs(d.y) + d.z;
  return vec2(d.x + d.y, d.x - d.y);
}
// Image basis of the view from direction v (towards the viewer).
void view_basis(vec3 v, out vec3 right, out vec3 up) {
  vec3 ref = abs(v.z) > 0.999 ? vec3(0.0, 1.0, 0.0) : vec3(0.0, 0.0, 1.0);
  right = normalize(cross(ref, v));
  up = cross(v, right);
}
)";

const char* kOctVertex = R"(
uniform vec3 u_center;   // model metres
uniform float u_radius;  // model metres
uniform vec3 u_lo, u_hi;  // the model's bounds (grown a little), model metres
uniform mat4 u_vp;
uniform vec3 u_eye;
uniform float u_focal_px;  // viewport height / (2 tan(fov_y / 2))
out vec3 v_world;
flat out vec3 v_eye_local;
flat out ivec2 v_steps;  // linear steps, bisection steps
flat out vec4 v_ph;
flat out float v_scale;
void main() {
  vec2 corner = vec2(gl_VertexID & 1, gl_VertexID >> 1) * 2.0 - 1.0;
  vec3 c = instance_to_world(u_center);
  float r = u_radius * i_scale.x;
  vec3 to_eye = u_eye - c;
  float dist = length(to_eye);
  vec3 n = to_eye / max(dist, 1e-6);
  vec3 ref = abs(n.z) > 0.999 ? vec3(0.0, 1.0, 0.0) : vec3(0.0, 0.0, 1.0);
  vec3 right = normalize(cross(ref, n)), up = cross(n, right);
  // The sphere's silhouette on the plane through its centre.
  float half_size = dist > 1.01 * r ? r * dist / sqrt(dist * dist - r * r) : 8.0 * r;
  vec2 lo = vec2(-half_size), hi = vec2(half_size);
  // Narrowed to the model box's silhouette on that plane when the whole box
  // is in front of the eye: a fragment costs about as much as the march
  // behind it whether or not the ray finds the object, and the sphere's
  // square holds a flat or long model's box several times over.
  vec2 blo = vec2(1e30), bhi = vec2(-1e30);
  bool in_front = true;
  for (int k = 0; k < 8; ++k) {
    vec3 b = vec3((k & 1) != 0 ? u_hi.x : u_lo.x, (k & 2) != 0 ? u_hi.y : u_lo.y,
                  (k & 4) != 0 ? u_hi.z : u_lo.z);
    vec3 ray = instance_to_world(b) - u_eye;
    float along = -dot(ray, n);  // distance in front of the eye, along the view of the centre
    in_front = in_front && along > 0.01 * dist;
    vec3 on_plane = ray * (dist / max(along, 1e-6)) - (c - u_eye);
    vec2 q = vec2(dot(on_plane, right), dot(on_plane, up));
    blo = min(blo, q);
    bhi = max(bhi, q);
  }
  if (in_front) {
    lo = max(lo, blo);
    hi = min(hi, bhi);
  }
  vec2 at = mix(lo, hi, corner * 0.5 + 0.5);
  v_world = c + at.x * right + at.y * up;
  v_eye_local = world_to_instance(u_eye);
  v_ph = i_pos_heading;
  v_scale = i_scale.x;
  // The march resolves the hit to a fraction of a screen pixel, not of a
  // texel: a small instance needs few steps (about one per two pixels of its
  // diameter), a large one the full 24 linear and 8 bisection steps.
  float size_px = 2.0 * r * u_focal_px / max(dist, 1e-6);
  int linear = int(clamp(ceil(0.5 * size_px), 8.0, 24.0));
  v_steps = ivec2(linear, linear == 24 ? 8 : 4);
  gl_Position = u_vp * vec4(v_world, 1.0);
}
)";

const char* kOctFragment = R"(
uniform sampler2D u_albedo;
uniform sampler2D u_geometry;
uniform vec3 u_center;
uniform float u_radius;
uniform vec3 u_lo, u_hi;  // the model's bounds (grown a little), model metres
uniform int u_views;
uniform int u_res;
uniform mat4 u_vp;
in vec3 v_world;
flat in vec3 v_eye_local;
flat in vec4 v_ph;
flat in float v_scale;
flat in ivec2 v_steps;
out vec4 o_color;

// The three views around the view direction: frame, direction, image basis.
ivec2 g_f[3];
vec3 g_v[3], g_right[3], g_up[3];

vec2 atlas_uv(int k, vec3 p) {  // p relative to the centre
  float h = 0.5 / float(u_res);
  vec2 uv = clamp(vec2(dot(p, g_right[k]), dot(p, g_up[k])) / u_radius * 0.5 + 0.5, h, 1.0 - h);
  return (vec2(g_f[k]) + uv) / float(u_views);
}
// How far p lies behind view k's recorded surface along its line (metres;
// negative: in front of it, or nothing recorded there).
float behind(int k, vec3 p) {
  float depth = packed_depth(texture(u_geometry, atlas_uv(k, p)));
  return depth < 1.0 ? u_radius * (1.0 - 2.0 * depth) - dot(p, g_v[k]) : -1e9;
}
// Solid: behind the recorded surface of each of the three views (the
// intersection of their depth-map solids, each of which holds the object;
// one view alone would extrude its surface into the others' disocclusions).
bool solid(vec3 p) {
  return behind(0, p) >= 0.0 && behind(1, p) >= 0.0 && behind(2, p) >= 0.0;
}

void main() {
  vec3 o = v_eye_local;
  float c = cos(v_ph.w), s = sin(v_ph.w);
  mat3 rot = mat3(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0);  // heading_rotate as a matrix
  vec3 d = normalize(transpose(rot) * (v_world - v_ph.xyz) / v_scale - o);
  // The three frames around the view direction (centre towards the eye).
  vec2 g = (oct_encode(normalize(o - u_center)) * 0.5 + 0.5) * float(u_views - 1);
  ivec2 cell = clamp(ivec2(floor(g)), ivec2(0), ivec2(u_views - 2));
  vec2 fr = clamp(g - vec2(cell), 0.0, 1.0);
  vec3 w;
  g_f[1] = cell + ivec2(1, 0);
  g_f[2] = cell + ivec2(0, 1);
  if (fr.x + fr.y < 1.0) { g_f[0] = cell; w = vec3(1.0 - fr.x - fr.y, fr.x, fr.y); }
  else { g_f[0] = cell + ivec2(1, 1); w = vec3(fr.x + fr.y - 1.0, 1.0 - fr.y, 1.0 - fr.x); }
  for (int k = 0; k < 3; ++k) {
    g_v[k] = oct_decode(vec2(g_f[k]) / float(u_views - 1) * 2.0 - 1.0);
    view_basis(g_v[k], g_right[k], g_up[k]);
  }
  // The ray's span inside the model's box.
  vec3 inv = 1.0 / d;
  vec3 ta = (u_lo - o) * inv, tb = (u_hi - o) * inv;
  vec3 tn = min(ta, tb), tf = max(ta, tb);
  float t0 = max(max(max(tn.x, tn.y), tn.z), 0.0), t1 = min(min(tf.x, tf.y), tf.z);
  if (t0 >= t1) discard;
  // Linear search along the span, then bisection.
  float lo = t0, hi = -1.0;
  for (int k = 0; k <= v_steps.x && hi < 0.0; ++k) {
    float t = mix(t0, t1, float(k) / float(v_steps.x));
    if (solid(o + t * d - u_center)) hi = t; else lo = t;
  }
  if (hi < 0.0) discard;
  for (int k = 0; k < v_steps.y; ++k) {
    float t = 0.5 * (lo + hi);
    if (solid(o + t * d - u_center)) hi = t; else lo = t;
  }
  vec3 q = o + hi * d - u_center;
  // Colour and normal from the views that recorded a surface at the hit
  // (within 1.5 texels), blended by their weights; none: the nearest surface.
  float tol = 1.5 * 2.0 * u_radius / float(u_res);
  vec3 albedo = vec3(0.0), n = vec3(0.0);
  float sum = 0.0, nearest_err = 1e9;
  int nearest = 0;
  vec4 gk[3], ak[3];
  for (int k = 0; k < 3; ++k) {
    vec2 uv = atlas_uv(k, q);
    gk[k] = texture(u_geometry, uv);
    ak[k] = texture(u_albedo, uv);
    float err = abs(behind(k, q));
    if (err < nearest_err) { nearest_err = err; nearest = k; }
    if (err <= tol && ak[k].a > 0.0) {
      float wk = w[k] + 1e-4;
      albedo += wk * ak[k].rgb / ak[k].a;
      n += wk * packed_normal(gk[k]);
      sum += wk;
    }
  }
  if (sum > 0.0) {
    albedo /= sum;
  } else {
    albedo = ak[nearest].a > 0.0 ? ak[nearest].rgb / ak[nearest].a : ak[nearest].rgb;
    n = packed_normal(gk[nearest]);
  }
  vec3 world = v_ph.xyz + rot * ((q + u_center) * v_scale);
  vec4 clip = u_vp * vec4(world, 1.0);
  gl_FragDepth = clip.z / clip.w;
  o_color = vec4(sun_lit(albedo, rot * n), 1.0);
}
)";

glm::vec3 oct_decode(glm::vec2 g) {
  const glm::vec2 a = glm::vec2(g.x + g.y, g.x - g.y) * 0.5f;
  const glm::vec3 d =
      glm::normalize(glm::vec3(a, std::max(1.f - std::abs(a.x) - std::abs(a.y), 0.f)));
  if (d.z >= kMinSinElevation) return d;
  const float c = std::sqrt(1.f - kMinSinElevation * kMinSinElevation);
  return glm::vec3(glm::normalize(glm::vec2(d)) * c, kMinSinElevation);
}

// The view (i, j): orthographic, the bounding sphere fills the tile, depth 0
// at the sphere's near side.
glm::mat4 view_capture(int i, int j, int views, glm::vec3 c, float r) {
  const glm::vec3 v = oct_decode(glm::vec2(i, j) / float(views - 1) * 2.f - 1.f);
  const glm::vec3 ref = std::abs(v.z) > 0.999f ? glm::vec3(0, 1, 0) : glm::vec3(0, 0, 1);
  const glm::vec3 right = glm::normalize(glm::cross(ref, v)), up = glm::cross(v, right);
  return from_rows(glm::vec4(right / r, -glm::dot(right, c) / r),
                   glm::vec4(up / r, -glm::dot(up, c) / r),
                   glm::vec4(-v / (2.f * r), glm::dot(v, c) / (2.f * r) + 0.5f));
}

/// kOctGlsl with the C++ side's constants.
std::string octahedral_glsl() {
  return fmt::format("const float kMinSinElevation = {};\n", kMinSinElevation) + kOctGlsl;
}

}  // namespace

gl::Program make_octahedral_program() {
  const std::string oct = octahedral_glsl();
  const std::string head = std::string("#version 450 core\n") + kObjectGlsl + oct;
  return gl::link_program(head + kOctVertex, std::string("#version 450 core\n") + kSunGlsl + oct +
                                                 objects::kPackedGeometryGlsl + kOctFragment);
}

}  // namespace objects

objects::OctahedralImpostor& GlModel::Impl::octahedral_impostor(int res, int views) {
  auto it = octahedral.find({res, views});
  if (it != octahedral.end()) return it->second;
  objects::OctahedralImpostor& o = octahedral[{res, views}];
  o.resolution = res;
  o.views = views;
  const int size = res * views;
  for (GLuint t : {o.albedo.id(), o.geometry.id()}) {
    // Depth is never interpolated across a silhouette (it would bend the
    // parallax off thin parts); colour and coverage are.
    const GLint filter = t == o.albedo.id() ? GL_LINEAR : GL_NEAREST;
    glTextureStorage2D(t, 1, GL_RGBA8, size, size);
    glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, filter);
    glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, filter);
    glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  }
  o.bytes = std::size_t(size) * size * 8;
  const glm::vec3 c = model.center();
  // The sphere through the farthest vertex, not the box's corners (which
  // an object seldom fills): the same texels cover less of nothing.
  float r = 0;
  for (const glm::vec3& p : model.positions) r = std::max(r, glm::length(p - c));
  r = std::max(r * 1.005f, 1e-6f);
  o.radius = r;
  const std::string what = fmt::format("octahedral-4deg-{}x{}", res, views);
  const objects::TextureLevel albedo{o.albedo.id(), GL_TEXTURE_2D,    size, size, 1,
                                     GL_RGBA,       GL_UNSIGNED_BYTE, 4};
  const objects::TextureLevel geometry{o.geometry.id(), GL_TEXTURE_2D,    size, size, 1,
                                       GL_RGBA,         GL_UNSIGNED_BYTE, 4};
  if (objects::load_impostor(cache, what, {albedo, geometry})) return o;
  const double t0 = objects::ms_now();
  gl::Texture depth(GL_TEXTURE_2D);
  glTextureStorage2D(depth.id(), 1, GL_DEPTH_COMPONENT32F, size, size);
  gl::Framebuffer fbo;
  objects::GlStateGuard guard;
  const GLenum bufs[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glNamedFramebufferDrawBuffers(fbo.id(), 2, bufs);
  glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT0, o.albedo.id(), 0);
  glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT1, o.geometry.id(), 0);
  glNamedFramebufferTexture(fbo.id(), GL_DEPTH_ATTACHMENT, depth.id(), 0);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
  const float clear_albedo[4] = {0, 0, 0, 0}, clear_geometry[4] = {0.5f, 0.5f, 1, 1}, far = 1.f;
  glClearNamedFramebufferfv(fbo.id(), GL_COLOR, 0, clear_albedo);
  glClearNamedFramebufferfv(fbo.id(), GL_COLOR, 1, clear_geometry);
  glClearNamedFramebufferfv(fbo.id(), GL_DEPTH, 0, &far);
  // Every view from the full mesh. A LOD level within a quarter texel keeps
  // the silhouette but smooths the normals, and the shading detail is most
  // of what an impostor would lose; even a level with a triangle per texel
  // costs visible quality.
  for (int j = 0; j < views; ++j)
    for (int i = 0; i < views; ++i) {
      glViewport(i * res, j * res, res, res);
      objects::capture_view(*this, objects::view_capture(i, j, views, c, r), true);
    }
  objects::store_impostor(cache, what, {albedo, geometry}, t0);
  return o;
}

void GlModel::Impl::draw_octahedral(const objects::OctahedralImpostor& o, GLsizei count,
                                    GLuint first, const Camera& camera) {
  const GLuint p = octahedral_program.id();
  glUseProgram(p);
  const glm::mat4 vp(gl::view_projection_reversed_z(camera));
  const glm::vec3 c = model.center();
  glUniformMatrix4fv(glGetUniformLocation(p, "u_vp"), 1, GL_FALSE, glm::value_ptr(vp));
  glUniform3fv(glGetUniformLocation(p, "u_center"), 1, glm::value_ptr(c));
  glm::vec3 lo, hi;
  objects::relief_box(model, lo, hi);
  glUniform3fv(glGetUniformLocation(p, "u_lo"), 1, glm::value_ptr(lo));
  glUniform3fv(glGetUniformLocation(p, "u_hi"), 1, glm::value_ptr(hi));
  glUniform1f(glGetUniformLocation(p, "u_radius"), o.radius);
  glUniform3f(glGetUniformLocation(p, "u_eye"), float(camera.position.x), float(camera.position.y),
              float(camera.position.z));
  GLint viewport[4];
  glGetIntegerv(GL_VIEWPORT, viewport);
  glUniform1f(glGetUniformLocation(p, "u_focal_px"),
              float(viewport[3] / (2 * std::tan(glm::radians(camera.fov_y_deg) / 2))));
  glUniform1i(glGetUniformLocation(p, "u_views"), o.views);
  glUniform1i(glGetUniformLocation(p, "u_res"), o.resolution);
  glUniform1i(glGetUniformLocation(p, "u_albedo"), 0);
  glUniform1i(glGetUniformLocation(p, "u_geometry"), 1);
  glBindTextureUnit(0, o.albedo.id());
  glBindTextureUnit(1, o.geometry.id());
  glBindVertexArray(instance_vao.id());
  glDrawArraysInstancedBaseInstance(GL_TRIANGLE_STRIP, 0, 4, count, first);
}

}  // namespace terrasprite
