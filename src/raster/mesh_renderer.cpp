// SPDX-License-Identifier: MIT
// Full-resolution and LOD rasterisation: one indexed draw from resident
// buffers, timed to glFinish (an honest baseline, DESIGN.md timing rules).
#include "terrasprite/raster/mesh_renderer.h"

#include <fmt/format.h>

#include "gl/frame_timer.h"
#include "gl/render_target.h"
#include "raster/terrain_gpu.h"
#include "terrasprite/common/error.h"

namespace terrasprite {
namespace {

int checked_samples(int samples) {
  const int most = gl::max_samples();
  if (samples < 1 || samples > most)
    throw InputError(
        fmt::format("samples {}: this GL offers 1 to {} samples a pixel", samples, most));
  return samples;
}

}  // namespace

struct MeshRenderer::State {
  Scene& scene;
  int quads;
  RasterOptions options;
};

MeshRenderer::MeshRenderer(Scene& scene, int width, int height, int quads, RasterOptions options)
    : GlRenderer(width, height, checked_samples(options.samples)),
      s_(std::make_unique<State>(State{scene, quads, options})) {
  scene.prepare(quads);  // upload now, not inside the first timed frame
}

MeshRenderer::~MeshRenderer() = default;

std::string MeshRenderer::name() const {
  return s_->quads <= 0 ? "full" : fmt::format("lod{}", s_->quads);
}

Frame MeshRenderer::draw(const Camera& camera) {
  TerrainGpu& terrain = s_->scene.terrain_gpu();
  const GpuMesh& mesh = terrain.mesh(s_->quads);
  const glm::mat4 vp(gl::view_projection_reversed_z(camera));
  timer().begin();
  begin_output();
  const DrapeFilter filter = s_->options.drape_filter;
  const DrapeSampling sampling = filter == DrapeFilter::kHand        ? DrapeSampling::kHand
                                 : filter == DrapeFilter::kTrilinear ? DrapeSampling::kTrilinear
                                 : filter == DrapeFilter::kHardware || s_->quads <= 0
                                     ? DrapeSampling::kHardware
                                     : DrapeSampling::kTrilinear;
  terrain.draw(mesh, vp, s_->options.lighting, sampling, s_->options.cull_back_faces);
  const long long triangles = mesh.triangles + s_->scene.draw_objects(camera);
  return make_frame(camera, timer().end(), s_->quads <= 0 ? FrameClass::kFull : FrameClass::kLod,
                    triangles);
}

}  // namespace terrasprite
