// SPDX-License-Identifier: MIT
// Multisampled render targets: edges resolve to coverage, every read resolves
// first, and sample counts GL does not offer are refused. About 0.1 s.
#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "gl/gl_objects.h"
#include "gl/render_target.h"
#include "terrasprite/common/error.h"
#include "terrasprite/gl/gl_context.h"
#include "terrasprite/raster/mesh_renderer.h"
#include "terrasprite/raster/scene.h"
#include "terrasprite/terrain/texture_gen.h"

namespace ts = terrasprite;

namespace {

ts::GlContext& context() {
  static ts::GlContext c;
  return c;
}

// A white triangle over the lower-left half of the target, its long edge the
// diagonal from (-1, 1) to (1, -1), in front of the far plane.
void draw_half(const ts::gl::RenderTarget& target) {
  static const ts::gl::Program program = ts::gl::link_program(
      R"(#version 450 core
void main() {
  vec2 p[3] = vec2[](vec2(-1.0, -1.0), vec2(1.0, -1.0), vec2(-1.0, 1.0));
  gl_Position = vec4(p[gl_VertexID], 0.5, 1.0);
})",
      R"(#version 450 core
out vec4 o_color;
void main() { o_color = vec4(1.0); })");
  const_cast<ts::gl::RenderTarget&>(target).bind_and_clear();
  static const ts::gl::VertexArray vao;
  glUseProgram(program.id());
  glBindVertexArray(vao.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

// Pixels whose red is strictly between the sky's and white's: edge coverage.
int partly_covered(const ts::Image& img, int sky_red) {
  int n = 0;
  for (std::size_t i = 0; i < img.rgba.size(); i += 4)
    n += img.rgba[i] > sky_red + 8 && img.rgba[i] < 247;
  return n;
}

}  // namespace

TEST(Multisample, EdgesResolveToCoverage) {
  context();
  if (ts::gl::max_samples() < 4) GTEST_SKIP() << "this GL offers fewer than 4 samples";
  ts::gl::RenderTarget single(32, 32), multi(32, 32, 4);
  single.bind_and_clear();
  const int sky_red = single.read_color().rgba[0];
  draw_half(single);
  draw_half(multi);
  const ts::Image a = single.read_color(), b = multi.read_color();
  // Single-sampled, a pixel is the sky or white; with 4 samples most of the
  // 32 pixels along the diagonal are partly covered.
  EXPECT_EQ(partly_covered(a, sky_red), 0);
  EXPECT_GE(partly_covered(b, sky_red), 24);
  // Away from the edge both agree.
  EXPECT_EQ(b.rgba[(30 * 32 + 1) * 4], 255);  // row 30 from the top, column 1: inside
  EXPECT_EQ(b.rgba[(1 * 32 + 30) * 4], a.rgba[(1 * 32 + 30) * 4]);  // outside: sky
  // The free read of the multisampled framebuffer resolves too.
  const ts::Image c = ts::gl::read_color(multi.framebuffer(), 32, 32);
  EXPECT_EQ(c.rgba, b.rgba);
  const std::vector<float> depth = ts::gl::read_depth_raw(multi.framebuffer(), 32, 32);
  EXPECT_FLOAT_EQ(depth[1 * 32 + 1], 0.5f);   // bottom-left row first: inside
  EXPECT_FLOAT_EQ(depth[30 * 32 + 30], 0.f);  // far: nothing drawn
}

TEST(Multisample, CountsGlDoesNotOfferAreRefused) {
  context();
  const int most = ts::gl::max_samples();
  EXPECT_THROW(ts::gl::RenderTarget(8, 8, 0), std::invalid_argument);
  EXPECT_THROW(ts::gl::RenderTarget(8, 8, most + 1), std::invalid_argument);
  ts::Terrain t;
  t.heights.width = t.heights.height = 9;
  t.heights.heights.assign(81, 0.f);
  t.texture = ts::checker_texture(2, 16);
  t.texture_name = "checker";
  ts::Scene scene(t);
  ts::RasterOptions o;
  o.samples = most + 1;
  EXPECT_THROW(ts::MeshRenderer(scene, 8, 8, 0, o), ts::InputError);
}
