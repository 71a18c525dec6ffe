// SPDX-License-Identifier: MIT
// Keyframes of the LOD-sprite technique (Chen et al. 1999, sections 3.1 and
// 3.3): render the full-resolution mesh straight into textures, then decide
// from its depth buffer which coarse polygons the keyframe can texture.
#include "sprite/keyframe.h"

#include <utility>

#include "sprite/keyframe_contrast.h"

namespace terrasprite {

Keyframe::Keyframe(int width, int height, bool measure_contrast)
    : target(width, height), contrast(measure_contrast) {}

void Keyframe::capture(TerrainGpu& scene, std::shared_ptr<const CoarseGrid> coarse, const Camera& c,
                       bool lighting, int pieces) {
  grid = std::move(coarse);
  camera = c;
  view_projection = glm::mat4(gl::view_projection_reversed_z(c));
  target.bind_and_clear();
  // Sky is transparent black: sprite fragments tell keyframe sky from
  // terrain, and bilinear taps across a silhouette stay premultiplied.
  glClearColor(0.f, 0.f, 0.f, 0.f);
  glClear(GL_COLOR_BUFFER_BIT);
  if (pieces > 1)
    scene.draw_in_pieces(scene.mesh(0), view_projection, lighting, pieces, [] { glFinish(); });
  else
    scene.draw(scene.mesh(0), view_projection, lighting);

  const std::vector<float> depth = target.read_depth(c.near_m, c.far_m);
  const DepthView dv{depth, target.width(), target.height()};
  const CoarseGrid& g = *grid;
  std::vector<std::uint8_t> vertex_visible(g.mesh_vertices.size());
  for (std::size_t v = 0; v < vertex_visible.size(); ++v)
    vertex_visible[v] = visible_in_keyframe(c, dv, g.mesh_vertices[v]) ? 1 : 0;
  const std::size_t cells = static_cast<std::size_t>(g.quad_count());
  std::vector<std::uint8_t> centre_visible(cells);
  fallback.assign(cells, 1);
  for (std::size_t q = 0; q < cells; ++q) {
    const bool centre = g.has_centre[q] && visible_in_keyframe(c, dv, g.centre[q]);
    centre_visible[q] = centre ? 1 : 0;
    // Paper 3.3: a polygon with any vertex hidden or outside the keyframe
    // takes the original texture. The centre vertex counts too: a ridge
    // inside the quad can hide its middle while its corners show.
    bool corners = true;
    for (int t = g.cell_first[q]; t < g.cell_first[q + 1]; ++t)
      corners = corners && vertex_visible[g.triangles[t]];
    fallback[q] = (corners && (centre || !g.has_centre[q])) ? 0 : 1;
  }
  samples = make_keyframe_samples(g, c, target.width(), target.height(), centre_visible);
  if (contrast) {  // uniform grids only (SpriteOptions)
    const Image color = target.read_color();
    QuadContrast qc = quad_contrast(g, c, target.width(), target.height(), color.rgba);
    samples.gradient = std::move(qc.gradient);
    samples.deviation = std::move(qc.deviation);
  }
  valid = true;
}

}  // namespace terrasprite
