// SPDX-License-Identifier: MIT
// The LOD-sprite policy (Chen, Swan, Kuo, Kaufman 1999): measure the error of
// the new view against the keyframe (Eq. 1-2); past the threshold render a new
// keyframe, otherwise a sprite frame from the coarse mesh.
#include "terrasprite/sprite_renderer.h"

#include <fmt/format.h>

#include <chrono>

#include "sprite/keyframe.h"
#include "sprite/sprite_pass.h"
#include "terrasprite/error.h"

namespace terrasprite {

struct SpriteRenderer::State {
  GlTerrain& scene;
  int width, height;
  SpriteOptions options;
  CoarseGrid grid;
  Keyframe key;
  gl::RenderTarget out;
  SpritePass pass;
  gl::Query timer{GL_TIME_ELAPSED};
  SpriteError last;
  std::string trigger;
  std::vector<std::uint8_t> flags;  // this frame's per-quad drape flags

  State(GlTerrain& s, int w, int h, const SpriteOptions& o)
      : scene(s),
        width(w),
        height(h),
        options(o),
        grid(make_coarse_grid(s.terrain().heights, o.lod_quads)),
        key(w, h, grid),
        out(w, h) {}
};

SpriteRenderer::SpriteRenderer(GlTerrain& scene, int width, int height, SpriteOptions options) {
  if (options.lod_quads < 1)
    throw InputError(fmt::format("--lod-quads {}: must be at least 1", options.lod_quads));
  if (!(options.threshold_px > 0))
    throw InputError(
        fmt::format("--threshold {}: must be a positive number of pixels", options.threshold_px));
  s_ = std::make_unique<State>(scene, width, height, options);
  // Upload both meshes now, not inside the first timed frame.
  scene.impl().mesh(0);
  scene.impl().mesh(options.lod_quads);
}

SpriteRenderer::~SpriteRenderer() = default;

std::string SpriteRenderer::name() const {
  return fmt::format("sprite{}", s_->options.lod_quads);
}
bool SpriteRenderer::has_keyframe() const {
  return s_->key.valid;
}
void SpriteRenderer::reset() {
  s_->key.valid = false;
  s_->last = {};
  s_->trigger.clear();
}
const SpriteError& SpriteRenderer::last_error() const {
  return s_->last;
}
const std::string& SpriteRenderer::last_trigger() const {
  return s_->trigger;
}
const SpriteOptions& SpriteRenderer::options() const {
  return s_->options;
}
const CoarseGrid& SpriteRenderer::grid() const {
  return s_->grid;
}
const std::vector<std::uint8_t>& SpriteRenderer::fallback_quads() const {
  return s_->key.fallback;
}

SpriteError SpriteRenderer::error(const Camera& camera) const {
  if (!s_->key.valid) return {};
  return sprite_error(s_->grid, s_->key.samples, camera);
}

bool SpriteRenderer::keyframe_due(const SpriteError& e) const {
  // Eq. (2): mean squared error over the samples > threshold^2.
  return e.value(s_->options.metric) > s_->options.threshold_px ||
         e.fallback_fraction() > s_->options.max_fallback_fraction ||
         e.resample_scale > s_->options.max_resample_scale;
}

void SpriteRenderer::make_keyframe(const Camera& camera) {
  s_->key.capture(s_->scene.impl(), s_->grid, camera, s_->options.lighting);
}

namespace {
enum Decision { kAuto = 0, kKey = 1, kSprite = 2 };
}

Frame SpriteRenderer::render_as(const Camera& camera, int d) {
  State& s = *s_;
  const SpriteRenderer& self = *this;
  GlTerrain::Impl& scene = s.scene.impl();
  const auto t0 = std::chrono::steady_clock::now();
  glBeginQuery(GL_TIME_ELAPSED, s.timer.id());
  SpriteError e = self.error(camera);
  bool key = d == kKey || (d == kAuto && (!s.key.valid || self.keyframe_due(e)));
  s.trigger.clear();
  if (!s.key.valid) {
    key = true;
    e = {};
    s.trigger = "first";
  } else if (d == kKey) {
    s.trigger = "forced";
  } else if (key) {
    const SpriteOptions& o = s.options;
    s.trigger = e.value(o.metric) > o.threshold_px                ? "error"
                : e.fallback_fraction() > o.max_fallback_fraction ? "fallback"
                                                                  : "scale";
  }
  gl::RenderTarget* result = &s.out;
  long long triangles = 0;
  if (key) {
    s.key.capture(scene, s.grid, camera, s.options.lighting);
    result = &s.key.target;
    triangles = scene.mesh(0).triangles;
  } else {
    const GpuMesh& coarse = scene.mesh(s.options.lod_quads);
    if (s.options.sharp_px > 0) {
      // Quads whose coarse geometry is already right at this distance take the drape texture.
      const double pixel = camera.pixel_angle(s.height);
      s.flags = s.key.fallback;
      for (std::size_t q = 0; q < s.flags.size(); ++q) {
        const double d = glm::length(s.grid.centre[q] - camera.position);
        if (s.grid.max_deviation[q] < s.options.sharp_px * pixel * d) s.flags[q] = 1;
      }
      glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
      glTextureSubImage2D(s.key.flags.id(), 0, 0, 0, s.grid.quads_x, s.grid.quads_y, GL_RED_INTEGER,
                          GL_UNSIGNED_BYTE, s.flags.data());
    }
    s.out.bind_and_clear();
    s.pass.draw(scene, coarse, s.grid.quads_x, s.key,
                glm::mat4(gl::view_projection_reversed_z(camera)), s.options.lighting);
    triangles = coarse.triangles;
  }
  glEndQuery(GL_TIME_ELAPSED);
  glFinish();
  const auto t1 = std::chrono::steady_clock::now();
  s.last = e;

  Frame f;
  f.ms = std::chrono::duration<double, std::milli>(t1 - t0).count();
  GLuint64 ns = 0;
  glGetQueryObjectui64v(s.timer.id(), GL_QUERY_RESULT, &ns);
  f.gpu_ms = ns / 1e6;
  f.triangles = triangles;
  f.cls = key ? "key" : "sprite";
  f.camera = camera;
  if (s.options.read_color) {
    f.color = result->read_color();
    for (std::size_t i = 0; i < f.color.rgba.size(); i += 4)  // keyframe sky is transparent black
      if (f.color.rgba[i + 3] == 0) {
        f.color.rgba[i] = kSkyColor[0];
        f.color.rgba[i + 1] = kSkyColor[1];
        f.color.rgba[i + 2] = kSkyColor[2];
        f.color.rgba[i + 3] = 255;
      }
  }
  if (s.options.read_depth) f.depth = result->read_depth(camera.near_m, camera.far_m);
  return f;
}

Frame SpriteRenderer::render(const Camera& camera) {
  return render_as(camera, kAuto);
}
Frame SpriteRenderer::render_keyframe(const Camera& camera) {
  return render_as(camera, kKey);
}
Frame SpriteRenderer::render_sprite(const Camera& camera) {
  return render_as(camera, kSprite);
}

}  // namespace terrasprite
