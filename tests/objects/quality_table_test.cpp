// SPDX-License-Identifier: MIT
// Quality tables on small sampling: identical renders score 1, quality does
// not fall as the object shrinks on screen, Table 1 picks the cheapest, the
// CLI writes the JSON contract and reuses its cache only for equal inputs.
#include "terrasprite/objects/quality_table.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <span>

#include "gl/render_target.h"
#include "object_test_util.h"
#include "terrasprite/common/error.h"
#include "terrasprite/gl/gl_context.h"
#include "test_util.h"

namespace ts = terrasprite;

namespace {

ts::QualityTable small_table(const ts::Model& m, ts::GlContext&) {
  ts::GlModel gl(m, ts::build_lod_chain(m));
  ts::TableOptions o;
  o.kinds = {ts::ObjectKind::kMesh, ts::ObjectKind::kRelief, ts::ObjectKind::kOctahedral};
  o.resolutions = {32, 64};
  o.sizes_px = {100, 50};
  o.angle_step_deg = 90;
  o.timing_instances = 2;
  return ts::measure_quality_table(gl, o);
}

// The teapot scan, 1 m tall.
ts::Model teapot(const std::string& data) {
  ts::ModelOptions mo;
  mo.height_m = 1.0;
  return ts::load_model(data + "/models_scans/teapot.obj", mo);
}

}  // namespace

TEST(QualityTable, IdenticalScoresOneAndQualityHoldsAsSizeShrinks) {
  const std::string data = tstest::shared_data();
  if (data.empty()) GTEST_SKIP() << "../shared/data is absent";
  ts::GlContext ctx;
  const ts::Model m = teapot(data);
  const ts::QualityTable t = small_table(m, ctx);
  ASSERT_FALSE(t.representations.empty());
  const ts::RepresentationQuality& full = t.representations[0];
  ASSERT_EQ(full.rep.kind, ts::ObjectKind::kMesh);
  ASSERT_EQ(full.rep.level, 0);
  for (const ts::QualitySample& s : full.samples) {
    EXPECT_DOUBLE_EQ(s.ssim, 1.0);
    EXPECT_TRUE(std::isinf(s.psnr));
  }
  // theta 0 (once) and 90 x 4 phi views, at 2 sizes.
  EXPECT_EQ(full.samples.size(), 10u);
  // A fixed representation does not get worse when drawn smaller (tolerance
  // 0.03 SSIM: nearest-texel impostors alias a little at small sizes).
  for (const ts::RepresentationQuality& q : t.representations) {
    EXPECT_GE(q.mean("ssim", 50), q.mean("ssim", 100) - 0.03)
        << ts::object_kind_name(q.rep.kind) << " " << q.rep.level << " " << q.rep.resolution;
    EXPECT_GT(q.ms_per_instance, 0.0);
    EXPECT_GT(q.bytes, 0u);
  }
  // More texels never hurt much; a finer mesh level beats a coarser one.
  auto find = [&](ts::ObjectKind k, int res) {
    for (const auto& q : t.representations)
      if (q.rep.kind == k && q.rep.resolution == res) return q.mean("ssim", 100);
    return double(NAN);
  };
  EXPECT_GT(find(ts::ObjectKind::kRelief, 64), find(ts::ObjectKind::kRelief, 32));
  EXPECT_GT(find(ts::ObjectKind::kOctahedral, 64), find(ts::ObjectKind::kOctahedral, 32));
  EXPECT_GT(t.representations[1].mean("ssim", 100), t.representations[4].mean("ssim", 100));
  // Table 1: level 0 always reaches SSIM 0.99, so pm always has an answer.
  for (const ts::TableEntry& e : t.table)
    if (e.kind == ts::ObjectKind::kMesh) {
      EXPECT_TRUE(e.choice.has_value());
    }
}

// A table's heading turns the model and its camera together (the scene's
// sun is fixed in the world): from a view in the model's own frame the
// silhouette is the same at every heading, while the side the sun lights
// changes. A table at two headings holds both, level 0 scoring 1 at each.
// CI cost: under 1 s.
TEST(QualityTable, AHeadingTurnsTheLightNotTheView) {
  const std::string data = tstest::shared_data();
  if (data.empty()) GTEST_SKIP() << "../shared/data is absent";
  ts::GlContext ctx;
  const ts::Model m = teapot(data);
  ts::GlModel gl(m, ts::build_lod_chain(m));
  constexpr int kSide = 96;
  ts::gl::RenderTarget target(kSide, kSide, 1);
  struct Shot {
    ts::Image color;
    std::vector<float> depth;
  };
  auto shot = [&](double heading, double phi) {
    const ts::Camera cam = ts::table_camera(m, phi, 60, 64, kSide, heading);
    const ts::ObjectInstance inst{glm::dvec3(0.0), heading, 1.0};
    target.bind_and_clear();
    gl.draw({ts::ObjectKind::kMesh, 0}, std::span(&inst, 1), cam);
    return Shot{target.read_color(), target.read_depth(cam.near_m, cam.far_m)};
  };
  // Pixels covered in one shot only, covered in both, and the mean luma
  // difference (0-255) where both are covered.
  auto compare = [](const Shot& a, const Shot& b) {
    int one = 0, both = 0;
    double luma = 0;
    for (std::size_t i = 0; i < a.depth.size(); ++i) {
      const bool ca = std::isfinite(a.depth[i]), cb = std::isfinite(b.depth[i]);
      if (ca != cb) ++one;
      if (!(ca && cb)) continue;
      ++both;
      const std::uint8_t *pa = &a.color.rgba[4 * i], *pb = &b.color.rgba[4 * i];
      luma += std::abs((0.299 * pa[0] + 0.587 * pa[1] + 0.114 * pa[2]) -
                       (0.299 * pb[0] + 0.587 * pb[1] + 0.114 * pb[2]));
    }
    return std::tuple(one, both, both ? luma / both : 0.0);
  };
  const Shot base = shot(0, 90);
  for (double heading : {90.0, 200.0}) {
    const auto [one, both, luma] = compare(base, shot(heading, 90));
    EXPECT_GT(both, 400) << heading;
    EXPECT_LT(one, both / 50) << heading;  // the same view: edge pixels at most
    EXPECT_GT(luma, 10.0) << heading;      // lit from another side (54-62 here)
  }
  // The view from the other side is another silhouette: the check can fail.
  const auto [mirror_one, mirror_both, mirror_luma] = compare(base, shot(0, 270));
  EXPECT_GT(mirror_one, mirror_both / 20);

  ts::TableOptions o;
  o.kinds = {ts::ObjectKind::kMesh};
  o.sizes_px = {50};
  o.angle_step_deg = 90;
  o.full_sphere = false;
  o.headings_deg = {0, 90};
  const ts::QualityTable t = ts::measure_quality_table(gl, o);
  ASSERT_GE(t.representations.size(), 2u);
  ASSERT_EQ(t.representations[0].samples.size(), 10u);  // 5 views x 2 headings
  int at90 = 0;
  for (const ts::QualitySample& s : t.representations[0].samples) {
    EXPECT_DOUBLE_EQ(s.ssim, 1.0);
    at90 += s.heading_deg == 90;
  }
  EXPECT_EQ(at90, 5);
  // A coarse level scores differently at the two headings somewhere.
  const auto& coarse = t.representations.back().samples;
  double most = 0;
  for (std::size_t k = 0; k < 5; ++k)
    most = std::max(most, std::abs(coarse[k].ssim - coarse[k + 5].ssim));
  EXPECT_GT(most, 1e-4);
  for (double bad : {-1.0, 360.0}) {
    o.headings_deg = {0, bad};
    EXPECT_THROW(ts::measure_quality_table(gl, o), ts::InputError) << bad;
  }
  o.headings_deg = {90, 90};
  EXPECT_THROW(ts::measure_quality_table(gl, o), ts::InputError);
}

// The walkthrough's far instances are 4-16 px: a table may sample them
// (from 4 px), and refuses sizes it cannot draw. CI cost: well under 1 s.
TEST(QualityTable, SizesFromFourPixelsAndNoneOutsideTheRange) {
  const std::string data = tstest::shared_data();
  if (data.empty()) GTEST_SKIP() << "../shared/data is absent";
  ts::GlContext ctx;
  const ts::Model m = teapot(data);
  ts::GlModel gl(m, ts::build_lod_chain(m));
  ts::TableOptions o;
  o.kinds = {ts::ObjectKind::kMesh};
  o.angle_step_deg = 90;
  for (int bad : {ts::kMinTableSizePx - 1, ts::kMaxTableSizePx + 1}) {
    o.sizes_px = {bad};
    EXPECT_THROW(ts::measure_quality_table(gl, o), ts::InputError) << bad;
  }
  o.sizes_px = {ts::kMinTableSizePx};
  // A view step under a degree would draw millions of views: refused, as is NaN.
  for (double bad : {0.001, ts::kMinTableAngleStepDeg / 2, 180.5, std::nan("")}) {
    o.angle_step_deg = bad;
    EXPECT_THROW(ts::measure_quality_table(gl, o), ts::InputError) << bad;
  }
  o.angle_step_deg = 90;
  const ts::QualityTable t = ts::measure_quality_table(gl, o);
  ASSERT_FALSE(t.representations.empty());
  ASSERT_EQ(t.representations[0].samples.size(), 5u);
  for (const ts::QualitySample& s : t.representations[0].samples) EXPECT_DOUBLE_EQ(s.ssim, 1.0);
}

// A flat model seen edge-on covers no pixel: neither image shows it, so
// the view scores as identical. Masked to no pixel, its scores were NaN,
// which made every nearby view's expected quality NaN (the default scene's
// forest and beetle at 4 px). CI cost: under 1 s.
TEST(QualityTable, AViewWhereNothingIsCoveredScoresAsIdentical) {
  ts::GlContext ctx;
  const ts::Model flat = tstest::colored_box(1.f, 1.f, 0.f);
  ts::GlModel gl(flat, ts::build_lod_chain(flat));
  ts::TableOptions o;
  o.kinds = {ts::ObjectKind::kMesh, ts::ObjectKind::kOctahedral};
  o.resolutions = {32};
  o.sizes_px = {ts::kMinTableSizePx, 16};
  o.angle_step_deg = 90;
  o.full_sphere = false;
  o.timing_instances = 1;
  const ts::QualityTable t = ts::measure_quality_table(gl, o);
  int edge_on = 0;
  for (const ts::RepresentationQuality& q : t.representations)
    for (const ts::QualitySample& s : q.samples) {
      EXPECT_TRUE(std::isfinite(s.ssim)) << ts::object_kind_name(q.rep.kind) << " theta "
                                         << s.theta_deg << " at " << s.size_px << " px";
      EXPECT_FALSE(std::isnan(s.psnr));
      if (q.rep.kind == ts::ObjectKind::kMesh && q.rep.level == 0 && s.theta_deg == 90) {
        EXPECT_DOUBLE_EQ(s.ssim, 1.0);
        ++edge_on;
      }
    }
  EXPECT_EQ(edge_on, 8);  // 4 azimuths x 2 sizes
}

TEST(QualityTable, CliJsonContractAndCache) {
  const std::string data = tstest::shared_data();
  if (data.empty()) GTEST_SKIP() << "../shared/data is absent";
  tstest::TempDir dir;
  const std::string args =
      "objects table --model " + data +
      "/models_kenney_nature/tree_oak_fall.glb --height-m 3 --kinds pm,relief,octahedral "
      "--resolutions 16 --sizes-px 64 --angle-step 120 --cache " +
      (dir / "cache");
  const tstest::CliResult first =
      tstest::run_cli(args + " --json " + (dir / "a.json") + " --out " + (dir / "a"));
  ASSERT_EQ(first.status, 0) << first.output;
  nlohmann::json j = nlohmann::json::parse(std::ifstream(dir / "a.json"));
  for (const char* k : {"model", "triangles", "representations", "table"})
    EXPECT_TRUE(j.contains(k)) << k;
  EXPECT_FALSE(j["cached"].get<bool>());
  for (const auto& r : j["representations"]) {
    for (const char* k : {"kind", "triangles", "bytes", "ms_per_instance", "samples"})
      EXPECT_TRUE(r.contains(k)) << k;
    EXPECT_TRUE(r.contains(r["kind"] == "pm" ? "level" : "resolution"));
  }
  EXPECT_TRUE(std::filesystem::exists(dir / "a/table1.md"));
  // Same inputs: read from the cache. Another parameter: measured again.
  const tstest::CliResult second =
      tstest::run_cli(args + " --json " + (dir / "b.json") + " --out " + (dir / "b"));
  ASSERT_EQ(second.status, 0) << second.output;
  EXPECT_TRUE(nlohmann::json::parse(std::ifstream(dir / "b.json"))["cached"].get<bool>());
  // A score that could not be measured is written as null and read back
  // (NaN, which the interpolator skips): the table stays cached, not
  // rejected as unreadable and measured again on every run.
  for (const auto& e : std::filesystem::directory_iterator(dir / "cache")) {
    if (e.path().extension() != ".json") continue;
    nlohmann::json cached = nlohmann::json::parse(std::ifstream(e.path()));
    cached["representations"][1]["samples"][0]["ssim"] = nullptr;
    std::ofstream(e.path()) << cached.dump();
  }
  const tstest::CliResult with_null =
      tstest::run_cli(args + " --json " + (dir / "n.json") + " --out " + (dir / "n"));
  ASSERT_EQ(with_null.status, 0) << with_null.output;
  EXPECT_EQ(with_null.output.find("cache file"), std::string::npos) << with_null.output;
  EXPECT_TRUE(nlohmann::json::parse(std::ifstream(dir / "n.json"))["cached"].get<bool>());
  const tstest::CliResult third =
      tstest::run_cli(args + " --views 6 --json " + (dir / "c.json") + " --out " + (dir / "c"));
  ASSERT_EQ(third.status, 0) << third.output;
  EXPECT_FALSE(nlohmann::json::parse(std::ifstream(dir / "c.json"))["cached"].get<bool>());
  // Two headings: another table, with its samples at both.
  const tstest::CliResult turned = tstest::run_cli(args + " --headings 0,180 --json " +
                                                   (dir / "h.json") + " --out " + (dir / "h"));
  ASSERT_EQ(turned.status, 0) << turned.output;
  j = nlohmann::json::parse(std::ifstream(dir / "h.json"));
  EXPECT_FALSE(j["cached"].get<bool>());
  EXPECT_EQ(j["options"]["headings_deg"], nlohmann::json::array({0.0, 180.0}));
  int at180 = 0;
  const auto& samples = j["representations"][0]["samples"];
  for (const auto& s : samples) at180 += s["heading_deg"] == 180.0;
  EXPECT_EQ(2 * at180, int(samples.size()));
  // Bad option values: exit 2 with one line.
  for (const char* bad_arg : {" --resolutions 8", " --headings 360", " --headings 0,0"}) {
    const tstest::CliResult bad = tstest::run_cli(args + bad_arg + " --out " + (dir / "d"));
    EXPECT_EQ(bad.status, 2) << bad_arg << ": " << bad.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "d"));
  }
}
