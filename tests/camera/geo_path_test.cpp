// SPDX-License-Identifier: MIT
// Geographic cameras: path keyframes in lon/lat and the look-at form
// (target, range, heading, pitch) on a terrain with a CRS.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "geo_test_util.h"
#include "terrasprite/camera/camera_path.h"
#include "terrasprite/camera/geo_view.h"
#include "terrasprite/common/error.h"
#include "terrasprite/terrain/terrain.h"
#include "test_util.h"

using namespace terrasprite;

namespace {

Heightfield geographic_plain() {
  return tstest::geographic_grid(100.f, "plain");
}

std::string what_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST(GeoPath, LonLatKeyframesAboveSeaOrGroundLookingAtAPlace) {
  const Heightfield h = geographic_plain();
  const KeyframePath p = parse_path_json(R"({"keyframes": [
      {"t": 0, "lon": 138.55, "lat": 35.15, "alt_m": 2000, "look_at": {"lon": 138.55, "lat": 35.45}},
      {"t": 1, "lon": 138.75, "lat": 35.45, "agl_m": 300, "yaw_deg": 270, "pitch_deg": -10}]})",
                                         "geo.json");
  const std::vector<Camera> c = sample_path(p, h, 2, 1.0);
  EXPECT_NEAR(c[0].position.x, 0, 1e-6);
  EXPECT_NEAR(c[0].position.y, -3000, 1e-6);
  EXPECT_NEAR(c[0].position.z, 2000, 1e-6);  // above sea level
  EXPECT_NEAR(c[0].yaw_deg, 0, 1e-6);        // looking north at the centre
  EXPECT_NEAR(c[0].pitch_deg, -std::atan2(1900, 3000) / kRadiansPerDegree, 1e-6);
  EXPECT_NEAR(c[1].position.x, 2000, 1e-6);
  EXPECT_NEAR(c[1].position.z, 400, 1e-6);  // 300 m above the 100 m ground
}

TEST(GeoPath, GeographicKeysNeedACrsAndValidPlaces) {
  Heightfield plain = geographic_plain();
  plain.geo.reset();
  const std::string k = R"({"keyframes": [{"t": 0, "lon": 138.55, "lat": 35.45, "agl_m": 10,
                                            "yaw_deg": 0}]})";
  EXPECT_NE(what_of([&] {
              path_from_json(k, "geo.json", plain, 1, 1.0);
            }).find("no coordinate reference system"),
            std::string::npos);
  const Heightfield h = geographic_plain();
  auto error = [&](const std::string& key) {
    return what_of([&] {
      path_from_json(R"({"keyframes": [{"t": 0, )" + key + "}]}", "geo.json", h, 1, 1.0);
    });
  };
  EXPECT_NE(error(R"("lon": 138.5, "lat": 35.4, "yaw_deg": 0)").find("alt_m"), std::string::npos);
  EXPECT_NE(
      error(R"("lon": 138.5, "lat": 35.4, "alt_m": 1, "agl_m": 1, "yaw_deg": 0)").find("one of"),
      std::string::npos);
  EXPECT_NE(error(R"("lon": 138.5, "lat": 135, "alt_m": 1, "yaw_deg": 0)").find("lat 135"),
            std::string::npos);
  EXPECT_NE(error(R"("lon": 138.5, "lat": 35.4, "position": [0,0,1], "alt_m": 1, "yaw_deg": 0)")
                .find("not both"),
            std::string::npos);
  EXPECT_NE(error(R"("position": [0, 0, 500], "look_at": {"lon": 150, "lat": 35.4})")
                .find("not on the terrain"),
            std::string::npos);
}

TEST(GeoView, LookAtPlacesTheEyeRangeMetresBackAlongHeadingAndPitch) {
  const Heightfield h = geographic_plain();
  LookAtView v{138.55, 35.45, 2000, 90, -30};  // look east, 30 degrees down
  const Camera c = look_at_camera(v, h, 1.0);
  EXPECT_NEAR(c.position.x, -2000 * std::cos(30 * kRadiansPerDegree), 1e-6);
  EXPECT_NEAR(c.position.y, 0, 1e-6);
  EXPECT_NEAR(c.position.z, 100 + 1000, 1e-6);
  EXPECT_NEAR(c.yaw_deg, 90, 1e-9);
  EXPECT_NEAR(c.pitch_deg, -30, 1e-9);
  const std::vector<Camera> orbit = look_at_orbit(v, h, 4, 1.0);
  EXPECT_NEAR(std::remainder(orbit[1].yaw_deg - 180, 360), 0, 1e-6);  // a quarter turn: south
  EXPECT_NEAR(glm::length(orbit[2].position - glm::dvec3(0, 0, 100)), 2000, 1e-6);
  v.pitch_deg = 20;  // looking up from below the target: the eye is underground
  EXPECT_NE(what_of([&] { look_at_camera(v, h, 1.0); }).find("below the ground"),
            std::string::npos);
  v.pitch_deg = -30;
  v.range_m = 0;
  EXPECT_NE(what_of([&] { look_at_camera(v, h, 1.0); }).find("--range 0"), std::string::npos);
}

TEST(GeoPath, TheFujiExamplePathFliesAboveMtFuji) {  // about 1.5 s: loads the 1201^2 tile
  const std::string d = tstest::shared_data();
  if (d.empty()) GTEST_SKIP() << "../shared/data is absent";
  TerrainOptions o;
  o.dem = d + "/srtm3_mt_fuji/mt_fuji_90m.tif";
  o.dem_given = true;
  const Terrain t = load_terrain(o);
  const auto path =
      load_path_file(std::string(TS_SOURCE_DIR) + "/examples/fuji-path.json", t.heights, 13, 1.0);
  for (const Camera& c : path) {
    EXPECT_GT(c.position.z, t.heights.sample(c.position.x, c.position.y));
    EXPECT_LT(c.pitch_deg, 0);
  }
  EXPECT_NEAR(path[0].position.z, 9000, 1e-6);
}
