// SPDX-License-Identifier: MIT
// The depth warp's banded forward splat against a plain serial one: every
// real pixel landed in row-major order, the nearest kept, ties to the first.
#include "warp/splat.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace terrasprite {
namespace {

// A real frame of random depths (some sky, some near) seen from a camera
// rolled, turned and moved, so spans of the real rows cross many bands of
// output rows and many real pixels compete for one output pixel.
TEST(Splat, BandsMatchASerialNearestWins) {
  const int sw = 611, sh = 97, w = 283, h = 150;  // several spans and bands
  Frame f;
  f.color = Image(sw, sh);
  f.depth.resize(std::size_t(sw) * sh);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> d(5.f, 60.f);
  for (std::size_t k = 0; k < f.depth.size(); ++k)
    f.depth[k] = k % 13 == 0 ? Frame::kSky : (k % 7 == 0 ? 5.f : d(rng));
  f.camera.position = {0, 0, 20};
  f.camera.pitch_deg = -20;
  f.camera.fov_y_deg = 50;
  f.camera.aspect = double(sw) / sh;
  Camera to = f.camera;
  to.position += glm::dvec3(1.5, 2.0, -0.5);
  to.roll_deg = 17;
  to.yaw_deg = 4;
  to.fov_y_deg = 40;
  to.aspect = double(w) / h;
  const warp::Reference ref(f);
  const warp::Pinhole out(to, w, h);
  const warp::SplatMap map(ref.cam, out);
  Warper::Scratch scratch;
  warp::splat(ref, map, w, h, scratch);

  std::vector<std::uint32_t> win(std::size_t(w) * h, warp::kEmpty);
  std::vector<float> depth(win.size());
  int landed = 0;
  for (int j = 0; j < sh; ++j)
    for (int i = 0; i < sw; ++i) {
      const float z = f.depth[std::size_t(j) * sw + i];
      float x, y, zt;
      if (!(z < Frame::kSky) || !map.land(i, j, z, x, y, zt)) continue;
      if (!(x >= 0.f && y >= 0.f && x < float(w) && y < float(h))) continue;
      const std::size_t at = std::size_t(int(y)) * w + int(x);
      ++landed;
      if (win[at] == warp::kEmpty || zt < depth[at]) {
        win[at] = warp::pack(i, j);
        depth[at] = zt;
      }
    }
  int filled = 0, differ = 0;
  for (std::size_t k = 0; k < win.size(); ++k) {
    differ += scratch.win[k] != win[k];
    if (win[k] != warp::kEmpty) {
      ++filled;
      EXPECT_EQ(scratch.win_depth[k], depth[k]) << k;
    }
  }
  ASSERT_GT(filled, 1000);
  ASSERT_GT(landed, filled + 100);  // real pixels competed for output pixels
  EXPECT_EQ(differ, 0);
}

}  // namespace
}  // namespace terrasprite
