// SPDX-License-Identifier: MIT
// The coherent voxel renderer's images, bit for bit: FNV-1a hashes of colour
// and depth for small static views at several pitches and rolls (both plane
// layouts: slope-indexed and polar, wrapped and not). The views whose
// vanishing point is near or in the image (-45, -60, -90) use the tiered polar
// layout, whose quality against the supersampled reference
// tests/voxel/tiered_layout_test.cpp checks.
// A speed change must keep these; a deliberate change of the images must
// record new ones (TS_PRINT_VOXEL_HASHES=1 prints them).
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "terrasprite/terrain/terrain.h"
#include "terrasprite/voxel/voxel_renderer.h"

namespace terrasprite {
namespace {

std::uint64_t fnv(const void* p, std::size_t n, std::uint64_t h) {
  const auto* b = static_cast<const unsigned char*>(p);
  for (std::size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
  return h;
}

struct View {
  double pitch, roll, yaw;
  VoxelVariant variant;
  std::uint64_t hash;
};

TEST(VoxelBits, StaticViewsKeepTheirImages) {
  TerrainOptions to;
  to.synthetic_size = 129;
  const Terrain t = load_terrain(to);
  const VoxelTerrain vt(t);
  const int W = 203, H = 117;  // odd sizes: partial strips and chunks
  const View views[] = {
      {-10, 0, 0, VoxelVariant::kCoherent, 0x7d6226e979cdf1daull},
      {-30, 0, 20, VoxelVariant::kCoherent, 0xc56d71cf48f3636aull},
      {-45, 15, 40, VoxelVariant::kCoherent, 0xbb55aa6833e09c4cull},
      {-60, 0, 0, VoxelVariant::kCoherent, 0xad295840782f8c94ull},
      {-90, 0, 0, VoxelVariant::kCoherent, 0xa2b74c575dc62cd8ull},
      {-25, -35, 70, VoxelVariant::kCoherent, 0xefaeab2d4b2c0abfull},
      {-10, 0, 0, VoxelVariant::kMultires, 0x031fd2d3d69e9937ull},
      {-30, 0, 20, VoxelVariant::kMultires, 0x421173218421df9full},
      {-60, 0, 0, VoxelVariant::kMultires, 0xfa88ccc5840ecd67ull},
      {20, 10, 0, VoxelVariant::kMultires, 0x2404e7c44ea61cf7ull},
  };
  const bool print = std::getenv("TS_PRINT_VOXEL_HASHES") != nullptr;
  for (const View& v : views) {
    VoxelOptions o;
    o.variant = v.variant;
    o.threads = 2;
    VoxelRenderer r(vt, W, H, o);
    const double E = t.heights.extent();
    Camera c;
    c.position = {0.0, -0.25 * E, double(t.heights.max_height()) + 0.15 * E};
    c.pitch_deg = v.pitch;
    c.roll_deg = v.roll;
    c.yaw_deg = v.yaw;
    c.fov_y_deg = 60;
    c.aspect = double(W) / H;
    fit_clip_planes(c, t.heights);
    const Frame f = r.draw(c);
    std::uint64_t h = fnv(f.color.rgba.data(), f.color.rgba.size(), 1469598103934665603ull);
    h = fnv(f.depth.data(), f.depth.size() * sizeof(float), h);
    if (print)
      std::printf("{%g, %g, %g, %s, 0x%016llxull},\n", v.pitch, v.roll, v.yaw,
                  v.variant == VoxelVariant::kCoherent ? "kCoherent" : "kMultires",
                  static_cast<unsigned long long>(h));
    EXPECT_EQ(h, v.hash) << "pitch " << v.pitch << " roll " << v.roll << " yaw " << v.yaw;
  }
}

}  // namespace
}  // namespace terrasprite
