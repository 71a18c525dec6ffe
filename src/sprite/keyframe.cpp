// SPDX-License-Identifier: MIT
// Keyframes of the LOD-sprite technique (Chen et al. 1999, sections 3.1 and
// 3.3): render the full-resolution mesh straight into textures, then decide
// from its depth buffer which coarse polygons the keyframe can texture.
#include "sprite/keyframe.h"

#include <cmath>
#include <utility>

#include "sprite/keyframe_contrast.h"

namespace terrasprite {

int KeyframeFraming::margin_px(int view_px) const {
  return int(std::lround(margin * view_px));
}
int KeyframeFraming::width(int view_width) const {
  return int(std::lround((view_width + 2 * margin_px(view_width)) * supersample));
}
int KeyframeFraming::height(int view_height) const {
  return int(std::lround((view_height + 2 * margin_px(view_height)) * supersample));
}
Camera KeyframeFraming::camera(const Camera& view, int view_width, int view_height) const {
  if (identity()) return view;
  // Widened in tan space by whole margin pixels, so that with supersample 1
  // the view's pixel centres fall on the keyframe's (an exact crop).
  const double fx = double(view_width + 2 * margin_px(view_width)) / view_width;
  const double fy = double(view_height + 2 * margin_px(view_height)) / view_height;
  Camera c = view;
  c.fov_y_deg = glm::degrees(2.0 * std::atan(fy * std::tan(0.5 * glm::radians(view.fov_y_deg))));
  c.aspect = view.aspect * fx / fy;
  return c;
}

Keyframe::Keyframe(int vw, int vh, bool measure_contrast, KeyframeFraming f)
    : target(f.width(vw), f.height(vh)),
      contrast(measure_contrast),
      framing(f),
      view_width(vw),
      view_height(vh) {}

void Keyframe::capture(TerrainGpu& scene, std::shared_ptr<const CoarseGrid> coarse,
                       const Camera& view, bool lighting, int pieces) {
  grid = std::move(coarse);
  camera = framing.camera(view, view_width, view_height);
  const Camera& c = camera;
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
  samples = make_keyframe_samples(g, c, target.width(), target.height(), centre_visible, view_width,
                                  view_height, view.fov_y_deg);
  if (contrast) {  // uniform grids only (SpriteOptions)
    const Image color = target.read_color();
    QuadContrast qc = quad_contrast(g, c, target.width(), target.height(), color.rgba);
    samples.gradient = std::move(qc.gradient);
    samples.deviation = std::move(qc.deviation);
  }
  valid = true;
}

}  // namespace terrasprite
