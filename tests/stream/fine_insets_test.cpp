// SPDX-License-Identifier: MIT
// Insets at their own resolution: `tile --inset FILE --fine-levels 5` over a
// 32 m base keeps a 1 m inset as sparse levels 0..4 of a 1 m combined grid.
// Inside the inset a sample is the inset's, outside the base's, the border
// blend is continuous; streamed tiles and frames equal the in-memory ones;
// failed inset reads fall back to the base; the marcher reads the fine levels
// when the camera is near the inset.
#include <cpl_conv.h>
#include <gdal.h>
#include <gtest/gtest.h>
#include <ogr_srs_api.h>

#include <array>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "stream_test_util.h"
#include "terrasprite/common/error.h"
#include "terrasprite/stream/streaming_tiles.h"
#include "terrasprite/stream/tiled_terrain.h"
#include "terrasprite/voxel/voxel_renderer.h"
#include "test_util.h"

namespace terrasprite {
namespace {

constexpr int kN = 33;                 // base samples a side, 32 m apart
constexpr int kK = 5;                  // fine levels: 1 m
constexpr int kF = (kN - 1) * 32 + 1;  // fine samples a side
constexpr int kI0 = 300, kIn = 257;    // the inset's first fine sample and its size
constexpr double kX0 = 500000, kY0 = 4000000;
constexpr int kW = 160, kH = 120;

float base_h(double i, double j) {
  return float(100 + 2 * i + j + 20 * std::sin(i * 0.4));
}
float detail(int x, int y) {
  return 5.f + 1.5f * std::sin(float(x) * 0.3f) * std::cos(float(y) * 0.21f);
}

std::string utm11() {
  return stream_test::utm_wkt(32611);
}

void write_tif(const std::string& path, int n, const double gt[6], const std::vector<float>& v) {
  GDALAllRegister();
  GDALDatasetH mem = GDALCreate(GDALGetDriverByName("MEM"), "", n, n, 1, GDT_Float32, nullptr);
  GDALSetGeoTransform(mem, const_cast<double*>(gt));
  GDALSetProjection(mem, utm11().c_str());
  ASSERT_EQ(GDALRasterIO(GDALGetRasterBand(mem, 1), GF_Write, 0, 0, n, n,
                         const_cast<float*>(v.data()), n, n, GDT_Float32, 0, 0),
            CE_None);
  GDALClose(GDALCreateCopy(GDALGetDriverByName("GTiff"), path.c_str(), mem, FALSE, nullptr, nullptr,
                           nullptr));
  GDALClose(mem);
}

// The base bilinear at fine sample (x, y).
float base_up(int x, int y) {
  const double i = x / 32.0, j = y / 32.0;
  const int a = std::min(int(i), kN - 2), b = std::min(int(j), kN - 2);
  const float fx = float(i - a), fy = float(j - b);
  const float t = base_h(a, b) + (base_h(a + 1, b) - base_h(a, b)) * fx;
  const float u = base_h(a, b + 1) + (base_h(a + 1, b + 1) - base_h(a, b + 1)) * fx;
  return t + (u - t) * fy;
}

struct Fixture {
  tstest::TempDir t;
  TileSetInfo set;
  Fixture() {
    std::vector<float> b(kN * kN), in(kIn * kIn);
    for (int j = 0; j < kN; ++j)
      for (int i = 0; i < kN; ++i) b[std::size_t(j) * kN + i] = base_h(i, j);
    const double gb[6] = {kX0, 32, 0, kY0, 0, -32};
    write_tif(t / "base.tif", kN, gb, b);
    // The inset: fine samples kI0.. (pixel centres on them), the base plus detail.
    for (int y = 0; y < kIn; ++y)
      for (int x = 0; x < kIn; ++x)
        in[std::size_t(y) * kIn + x] = base_up(kI0 + x, kI0 + y) + detail(x, y);
    const double gi[6] = {kX0 + 16 + kI0 - 0.5, 1, 0, kY0 - 16 - kI0 + 0.5, 0, -1};
    write_tif(t / "inset.tif", kIn, gi, in);
    // blend=0 into the base grid: a base sample inside the inset is the inset's.
    auto r = tstest::run_cli("tile --dem " + (t / "base.tif") + " --inset " + (t / "inset.tif") +
                             ":blend=8 --fine-levels 5 --tile-size 16 --color-compress DEFLATE "
                             "--out " +
                             (t / "tiles"));
    EXPECT_EQ(r.status, 0) << r.output;
    set = read_tile_set(t / "tiles");
  }
};

// Height of fine sample (x, y) as a reader sees it: level 0 where a tile
// holds it, else the base (level kK) bilinear, as the marcher falls back.
float sample(const TerrainTiles& s, int x, int y, bool* fine = nullptr) {
  const int lg = s.grid().tile_log2;
  auto at = [&](const TileBlock* b, int i, int j) {
    return b->height[std::ptrdiff_t(j - b->y0) * b->stride + (i - b->x0)];
  };
  if (const TileBlock* b = s.tile(0, std::min(x, kF - 2) >> lg, std::min(y, kF - 2) >> lg)) {
    if (fine) *fine = true;
    return at(b, x, y);
  }
  if (fine) *fine = false;
  const double i = x / 32.0, j = y / 32.0;
  const int a = std::min(int(i), kN - 2), c = std::min(int(j), kN - 2);
  const TileBlock* b = s.tile(kK, a >> lg, c >> lg);
  EXPECT_NE(b, nullptr);
  const float fx = float(i - a), fy = float(j - c);
  const float top = at(b, a, c) + (at(b, a + 1, c) - at(b, a, c)) * fx;
  const float bot = at(b, a, c + 1) + (at(b, a + 1, c + 1) - at(b, a, c + 1)) * fx;
  return top + (bot - top) * fy;
}

// A camera 60 m over the inset looking across it.
Camera over_inset(double yaw) {
  const double x = kI0 + 40 - (kF - 1) / 2.0, y = (kF - 1) / 2.0 - (kI0 + 128);
  Camera c;
  c.position = {x, y, base_up(kI0 + 40, kI0 + 128) + 65.0};
  c.yaw_deg = yaw;
  c.pitch_deg = -25;
  c.aspect = double(kW) / kH;
  return c;
}

TEST(FineInsets, InsideIsTheInsetAtItsOwnSpacingOutsideTheBaseBlendContinuous) {
  Fixture f;
  ASSERT_TRUE(f.set.fine_set);
  const TerrainGrid g = combined_grid(f.set);
  EXPECT_EQ(g.width, kF);
  EXPECT_NEAR(g.spacing_x, 1.0, 1e-12);
  EXPECT_EQ(g.sparse_levels, kK);
  EXPECT_EQ(g.coarsest_level, f.set.grid.coarsest_level + kK);
  ResidentTiles mem(f.set);
  // Inside (8+ samples from the edge): the inset's own 1 m samples.
  for (auto [x, y] : {std::pair{128, 128}, {20, 200}, {240, 15}, {9, 9}}) {
    bool fine = false;
    EXPECT_NEAR(sample(mem, kI0 + x, kI0 + y, &fine), base_up(kI0 + x, kI0 + y) + detail(x, y),
                2e-3)
        << x << "," << y;
    EXPECT_TRUE(fine);
  }
  // Outside: no fine tile, the base's own samples (composited one base cell
  // (32 samples) away at most, so these are the base untouched).
  for (auto [x, y] : {std::pair{40, 40}, {1000, 900}, {kI0 + 128, 900}, {200, kI0 + 128}}) {
    bool fine = true;
    EXPECT_NEAR(sample(mem, x, y, &fine), base_up(x, y), 1e-3) << x << "," << y;
    EXPECT_FALSE(fine) << x << "," << y;
  }
  // Across the west border along a row: no step beyond the blend of the
  // ~6.5 m detail over 8 samples plus the slope; the edge reads the base's.
  const int row = kI0 + 128;
  float steepest = 0;
  for (int x = kI0 - 40; x < kI0 + 40; ++x)
    steepest = std::max(steepest, std::abs(sample(mem, x + 1, row) - sample(mem, x, row)));
  EXPECT_LT(steepest, 6.5f / 8 + 2.f);
  EXPECT_NEAR(sample(mem, kI0, row), base_up(kI0, row), 0.5);
  // The base's bounds cover the inset's detail (empty-space skipping).
  const TileBlock* top = mem.tile(g.bound_levels - 1, 0, 0);
  ASSERT_NE(top, nullptr);
  EXPECT_GE(top->max_height, base_up(kI0 + 128, kI0 + 128) + 5.f);
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(f.t / "tiles/tiles.json"));
  EXPECT_EQ(j["fine"]["levels"], kK);
}

// Counts the renderer's lookups of fine levels.
class Counting final : public TerrainTiles {
 public:
  explicit Counting(const TerrainTiles& s) : s_(s) {}
  const TerrainGrid& grid() const override { return s_.grid(); }
  const TileBlock* tile(int level, int tx, int ty) const override {
    const TileBlock* b = s_.tile(level, tx, ty);
    if (b && level < kK) fine_hits.fetch_add(1);
    return b;
  }
  mutable std::atomic<long long> fine_hits{0};

 private:
  const TerrainTiles& s_;
};

TEST(FineInsets, StreamedEqualsInMemoryFaultsFallBackAndTheMarcherReadsFineLevels) {
  Fixture f;
  ResidentTiles mem(f.set);
  StreamOptions o;
  o.image_height = kH;
  o.pinned_share = 0;
  StreamingTiles s(f.set, o);
  const Camera c = over_inset(90);
  // The march reaches the fine levels near the inset.
  Counting counted(mem);
  VoxelRenderer rc(counted, kW, kH);
  rc.draw(c);
  EXPECT_GT(counted.fine_hits.load(), 1000);
  // Streamed: once resident, the same frame.
  VoxelRenderer rm(mem, kW, kH), rs(s, kW, kH);
  const StreamFrameStats st = stream_test::draw_until_resident(rs, s, c);
  ASSERT_EQ(st.degraded_samples, 0);
  EXPECT_GT(st.resident_tiles, 0);
  const Frame a = rm.draw(c), b = rs.draw(c);
  ASSERT_EQ(a.color.rgba, b.color.rgba);
  ASSERT_EQ(a.depth, b.depth);

  // Every fine read failing: counted, survived, served by the base.
  StreamOptions fo = o;
  fo.fail_read = [](int level, int, int) { return level < kK; };
  StreamingTiles bad(f.set, fo);
  VoxelRenderer rb(bad, kW, kH);
  int failed = 0;
  for (int k = 0; k < 4; ++k) {
    failed += bad.update(c).failed;
    rb.draw(c);
    bad.settle();
  }
  failed += bad.update(c).failed;
  EXPECT_GT(failed, 0);
  EXPECT_EQ(bad.injected_faults(), bad.failed_tiles());
  bool fine = true;
  EXPECT_NEAR(sample(bad, kI0 + 128, kI0 + 128, &fine), base_up(kI0 + 128, kI0 + 128) + 5.f, 8.f);
  EXPECT_FALSE(fine);
  const Frame d = rb.draw(c);
  EXPECT_NE(d.color.rgba, a.color.rgba);  // the inset's detail is what is missing
}

TEST(FineInsets, BadFineLevelsExitWith2) {
  tstest::TempDir t;
  auto r = tstest::run_cli("tile --synthetic-size 65 --fine-levels 3 --out " + (t / "x"));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_FALSE(std::filesystem::exists(t.path / "x"));
}

}  // namespace
}  // namespace terrasprite
