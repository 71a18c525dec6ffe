// SPDX-License-Identifier: MIT
// Places and voids at the command line, on the real DEMs in ../shared/data:
// --look-at, the nodata share and fill method, --fill, objects scene's
// camera and placed instances.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "test_util.h"

namespace fs = std::filesystem;

namespace {

std::string fuji() {
  const std::string d = tstest::shared_data();
  return d.empty() ? d : d + "/srtm3_mt_fuji/mt_fuji_90m.tif";
}

void expect_one_line_error(const std::string& args, const std::string& fragment) {
  const tstest::CliResult r = tstest::run_cli(args);
  EXPECT_EQ(r.status, 2) << args << "\n" << r.output;
  EXPECT_NE(r.output.find(fragment), std::string::npos) << args << "\n" << r.output;
  EXPECT_LE(std::count(r.output.begin(), r.output.end(), '\n'), 1) << args << "\n" << r.output;
}

nlohmann::json read_json(const std::string& f) {
  return nlohmann::json::parse(std::ifstream(f));
}

}  // namespace

TEST(PlacesCli, LookAtNeedsACrsAndAPlaceOnTheTerrain) {  // about 5 s: three loads of the tile
  const std::string r = "render --synthetic-size 33 --frames 1 --size 16x16 --out o ";
  expect_one_line_error(r + "--look-at 138.7,35.3", "no coordinate reference system");
  expect_one_line_error(r + "--range 100", "need --look-at");
  expect_one_line_error(r + "--look-at 138.7", "expected LON,LAT");
  expect_one_line_error(r + "--fill none", "only info takes it");
  expect_one_line_error("tile --synthetic-size 33 --fill none --out t", "only info takes it");
  if (fuji().empty()) GTEST_SKIP() << "../shared/data is absent";
  const std::string f = "render --dem " + fuji() + " --frames 1 --size 16x16 --out o ";
  expect_one_line_error(f + "--look-at 140.5,35.3", "not on the terrain");
  expect_one_line_error(f + "--look-at 138.7,95", "latitude");
  expect_one_line_error(f + "--look-at 138.7274,35.3606 --pitch 30", "below the ground");
}

TEST(PlacesCli, RendersMtFujiByLonLatAndStatesItsVoids) {  // about 9 s: four loads of the tile
  if (fuji().empty()) GTEST_SKIP() << "../shared/data is absent";
  tstest::TempDir tmp;
  const tstest::CliResult r = tstest::run_cli(
      "render --dem " + fuji() +
      " --look-at 138.7274,35.3606 --range 15000 --heading 0 --pitch -20 --frames 1 --size "
      "32x32 --out " +
      tmp / "la");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(fs::exists(tmp / "la/frame_0000.png"));
  const tstest::CliResult i = tstest::run_cli("info --dem " + fuji() + " --json " + tmp / "i.json");
  ASSERT_EQ(i.status, 0) << i.output;
  EXPECT_NE(i.output.find("(0.2% of the grid) filled by AMLE"), std::string::npos) << i.output;
  // Where it lies, in the terms --look-at takes (the tile spans 138..139 E, 35..36 N).
  EXPECT_NE(i.output.find("CRS EPSG:4326 (WGS 84); longitude 138.00000 .. 139.00000, latitude "
                          "35.00000 .. 36.00000"),
            std::string::npos)
      << i.output;
  const nlohmann::json place = read_json(tmp / "i.json")["place"];
  EXPECT_EQ(place["crs"], "EPSG:4326 (WGS 84)");
  for (int k = 0; k < 4; ++k)
    EXPECT_NEAR(place["lonlat_box"][k].get<double>(), (k % 2 ? 35.0 : 138.0) + (k >= 2), 1e-6);
  const nlohmann::json n = read_json(tmp / "i.json")["nodata"];
  EXPECT_NEAR(n["filled_fraction"].get<double>(), 2437.0 / (1201 * 1201), 1e-9);
  EXPECT_EQ(n["fill_method"], "amle");
  ASSERT_EQ(
      tstest::run_cli("info --fill gdal --dem " + fuji() + " --json " + tmp / "g.json").status, 0);
  EXPECT_EQ(read_json(tmp / "g.json")["nodata"]["fill_method"], "gdal");
  ASSERT_EQ(
      tstest::run_cli("info --fill none --dem " + fuji() + " --json " + tmp / "n.json").status, 0);
  EXPECT_EQ(read_json(tmp / "n.json")["nodata"]["fill_method"], "none");
}

TEST(PlacesCli, ObjectsSceneReportsItsCameraAndWritesPlacedInstances) {  // about 3 s
  const std::string d = tstest::shared_data();
  if (d.empty()) GTEST_SKIP() << "../shared/data is absent";
  tstest::TempDir tmp;
  std::ofstream(tmp / "s.json") << R"({"models": [{"name": "pot", "file": ")" << d
                                << R"(/models_scans/teapot.obj", "height_m": 20}],
      "scatter": [{"model": "pot", "count": 5, "seed": 2, "min_spacing_m": 40}]})";
  const tstest::CliResult r =
      tstest::run_cli("objects scene --synthetic-size 65 --scene " + tmp / "s.json" +
                      " --frames 1 --size 64x64 "
                      "--cache off --out " +
                      tmp / "sc");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("camera: eye ["), std::string::npos) << r.output;
  const nlohmann::json s = read_json(tmp / "sc/scene.json");
  EXPECT_EQ(s["camera"]["position"].size(), 3u);
  EXPECT_TRUE(s["camera"].contains("yaw_deg"));
  const nlohmann::json p = read_json(tmp / "sc/placed.json");
  ASSERT_EQ(p["instances"].size(), 5u);
  EXPECT_EQ(p["instances"][0]["position"].size(), 3u);
  // The placed file is a scene file: objects scene reads it back.
  EXPECT_EQ(tstest::run_cli("objects scene --synthetic-size 65 --scene " + tmp / "sc/placed.json" +
                            " --frames 1 --size 32x32 --cache off --out " + tmp / "again")
                .status,
            0);
}
