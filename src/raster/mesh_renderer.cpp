// SPDX-License-Identifier: MIT
// Full-resolution and LOD rasterisation: one indexed draw from resident
// buffers, timed to glFinish (an honest baseline, DESIGN.md timing rules).
#include "terrasprite/mesh_renderer.h"

#include <fmt/format.h>

#include <chrono>

#include "gl/render_target.h"
#include "raster/gl_terrain.h"

namespace terrasprite {

struct MeshRenderer::State {
  GlTerrain& scene;
  int quads;
  RasterOptions options;
  gl::RenderTarget target;
  gl::Query timer{GL_TIME_ELAPSED};
};

MeshRenderer::MeshRenderer(GlTerrain& scene, int width, int height, int quads,
                           RasterOptions options)
    : s_(std::make_unique<State>(State{scene, quads, options, gl::RenderTarget(width, height)})) {
  scene.impl().mesh(quads);  // upload now, not inside the first timed frame
}

MeshRenderer::~MeshRenderer() = default;

std::string MeshRenderer::name() const {
  return s_->quads <= 0 ? "full" : fmt::format("lod{}", s_->quads);
}

Frame MeshRenderer::render(const Camera& camera) {
  GlTerrain::Impl& scene = s_->scene.impl();
  const GpuMesh& mesh = scene.mesh(s_->quads);
  const glm::mat4 vp(gl::view_projection_reversed_z(camera));
  const auto t0 = std::chrono::steady_clock::now();
  glBeginQuery(GL_TIME_ELAPSED, s_->timer.id());
  s_->target.bind_and_clear();
  scene.draw(mesh, vp, s_->options.lighting);
  glEndQuery(GL_TIME_ELAPSED);
  glFinish();
  const auto t1 = std::chrono::steady_clock::now();

  Frame f;
  f.ms = std::chrono::duration<double, std::milli>(t1 - t0).count();
  GLuint64 ns = 0;
  glGetQueryObjectui64v(s_->timer.id(), GL_QUERY_RESULT, &ns);
  // GPU time inside the span cannot exceed its wall time; llvmpipe reports
  // nonsense (minutes) for the first query of a process, so such a value is dropped.
  f.gpu_ms = ns / 1e6 <= f.ms * 1.05 + 0.1 ? ns / 1e6 : -1.0;
  f.triangles = mesh.triangles;
  f.cls = s_->quads <= 0 ? "full" : "lod";
  f.camera = camera;
  f.color = s_->target.read_color();
  if (s_->options.read_depth) f.depth = s_->target.read_depth(camera.near_m, camera.far_m);
  return f;
}

}  // namespace terrasprite
