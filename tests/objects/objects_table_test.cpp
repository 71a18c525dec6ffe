// SPDX-License-Identifier: MIT
// `objects table` in-process: a small pyramid's table measured once, read
// back from the cache the second time, its JSON read back unchanged, and
// Table 1 written from it.
#include "terrasprite/experiment/objects/objects_table.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "terrasprite/common/error.h"
#include "terrasprite/objects/quality_table_json.h"
#include "terrasprite/report/objects_report.h"
#include "test_util.h"

namespace ts = terrasprite;

namespace {

// A square pyramid 3 m tall (6 triangles) written into `dir`, measured from
// 5 views (theta 0 once, theta 90 at 4 azimuths) at one size.
ts::ObjectsTableOptions pyramid_table(const tstest::TempDir& dir) {
  std::ofstream(dir / "pyramid.obj") << "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv 0 3 0\n"
                                        "f 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\nf 1 3 2\nf 1 4 3\n";
  ts::ObjectsTableOptions o;
  o.model_file = dir / "pyramid.obj";
  o.model.height_m = 3;
  o.table.kinds = {ts::ObjectKind::kMesh, ts::ObjectKind::kRelief};
  o.table.resolutions = {16};
  o.table.sizes_px = {32};
  o.table.angle_step_deg = 90;
  o.cache_dir = dir / "cache";
  return o;
}

}  // namespace

TEST(ObjectsTable, MeasuredOnceThenReadFromTheCache) {
  tstest::TempDir dir;
  ts::ObjectsTableOptions o = pyramid_table(dir);
  int progress_calls = 0;
  o.progress = [&](int done, int total) {
    ++progress_calls;
    EXPECT_LE(done, total);
  };
  const ts::ObjectsTableResult first = ts::run_objects_table(o);
  EXPECT_FALSE(first.cached);
  EXPECT_GT(progress_calls, 0);
  EXPECT_TRUE(std::filesystem::exists(first.cache_file)) << first.cache_file;
  EXPECT_EQ(first.cache_file.parent_path(), std::filesystem::path(o.cache_dir));
  // The LOD chain and the one relief impostor were built (no cache entry yet).
  EXPECT_EQ(first.representation_cache.hits, 0);
  EXPECT_EQ(first.representation_cache.misses, 2);
  ASSERT_FALSE(first.table.representations.empty());
  const ts::RepresentationQuality& full = first.table.representations[0];
  EXPECT_EQ(full.rep.kind, ts::ObjectKind::kMesh);
  EXPECT_EQ(full.triangles, 6);
  ASSERT_EQ(full.samples.size(), 5u);
  for (const ts::QualitySample& s : full.samples) EXPECT_DOUBLE_EQ(s.ssim, 1.0);

  progress_calls = 0;
  const ts::ObjectsTableResult second = ts::run_objects_table(o);
  EXPECT_TRUE(second.cached);
  EXPECT_EQ(progress_calls, 0);
  EXPECT_EQ(second.cache_file, first.cache_file);
  EXPECT_EQ(second.representation_cache.hits + second.representation_cache.misses, 0);
  ASSERT_EQ(second.table.representations.size(), first.table.representations.size());
  for (std::size_t i = 0; i < first.table.representations.size(); ++i) {
    const auto& a = first.table.representations[i].samples;
    const auto& b = second.table.representations[i].samples;
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t k = 0; k < a.size(); ++k) EXPECT_DOUBLE_EQ(a[k].ssim, b[k].ssim);
  }

  // Without the cache: measured again, nothing read or stored.
  o.use_cache = false;
  const ts::ObjectsTableResult fresh = ts::run_objects_table(o);
  EXPECT_FALSE(fresh.cached);
  EXPECT_TRUE(fresh.cache_file.empty());
  EXPECT_EQ(fresh.representation_cache.hits + fresh.representation_cache.misses, 0);
}

TEST(ObjectsTable, JsonReadsBackAndTheReportSaysWhatItRead) {
  tstest::TempDir dir;
  const ts::ObjectsTableOptions o = pyramid_table(dir);
  const ts::ObjectsTableResult r = ts::run_objects_table(o);
  const nlohmann::json j = ts::table_json(r.table, o.table);
  EXPECT_EQ(j["format"], ts::kQualityTableFormat);
  // Identical images: infinite PSNR, written as "inf" and read back as such.
  EXPECT_EQ(j["representations"][0]["samples"][0]["psnr"], "inf");
  const ts::QualityTable back = ts::table_from_json(j);
  EXPECT_EQ(back.model, r.table.model);
  EXPECT_EQ(back.triangles, 6);
  ASSERT_EQ(back.table.size(), r.table.table.size());
  EXPECT_TRUE(std::isinf(back.representations[0].samples[0].psnr));
  EXPECT_EQ(ts::table_json(back, o.table), j);

  const nlohmann::json report = ts::report::objects_table_json(r, o.table);
  EXPECT_FALSE(report["cached"].get<bool>());
  EXPECT_EQ(report["representation_cache"]["misses"], 2);
  EXPECT_EQ(report["triangles"], 6);
  // Table 1: the full mesh reaches every target at the one size, as level 0 at least.
  const std::string md = ts::report::table1_markdown(r.table, o.table);
  EXPECT_NE(md.find("| pm ssim | 0.9 | 0.95 | 0.98 | 0.99 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| relief psnr |"), std::string::npos) << md;

  nlohmann::json bad = j;
  bad["format"] = "another";
  EXPECT_THROW(ts::table_from_json(bad), ts::InputError);
}
