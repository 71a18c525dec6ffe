// SPDX-License-Identifier: MIT
// Real data read right: geotransform signs, rotation, drape footprints that
// miss the heights, an image's own nodata, implausible encoded heights.
#include <cpl_conv.h>
#include <gdal.h>
#include <gtest/gtest.h>
#include <ogr_srs_api.h>

#include "terrasprite/terrain/image_io.h"
#include "terrasprite/common/error.h"
#include "terrasprite/terrain/terrain.h"
#include "terrasprite/terrain/dem_loader.h"
#include "test_util.h"

using namespace terrasprite;

namespace {

// A GeoTIFF of `bands` bands of `type` in UTM 33N (EPSG:32633); `v` is band-sequential.
template <class T>
void write_tif(const std::string& path, int w, int h, int bands, GDALDataType type,
               const std::vector<T>& v, const double gt[6]) {
  GDALAllRegister();
  GDALDatasetH ds =
      GDALCreate(GDALGetDriverByName("GTiff"), path.c_str(), w, h, bands, type, nullptr);
  ASSERT_NE(ds, nullptr);
  GDALSetGeoTransform(ds, const_cast<double*>(gt));
  OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
  OSRImportFromEPSG(srs, 32633);
  char* wkt = nullptr;
  OSRExportToWkt(srs, &wkt);
  GDALSetProjection(ds, wkt);
  CPLFree(wkt);
  OSRDestroySpatialReference(srs);
  ASSERT_EQ(GDALDatasetRasterIO(ds, GF_Write, 0, 0, w, h, const_cast<T*>(v.data()), w, h, type,
                                bands, nullptr, 0, 0, 0),
            CE_None);
  GDALClose(ds);
}

TerrainOptions dem(const std::string& path) {
  TerrainOptions o;
  o.dem = path;
  return o;
}

// 3 x 2 heights, row 0 north: 1 2 3 / 4 5 6.
const std::vector<std::int16_t> kNorthUp = {1, 2, 3, 4, 5, 6};

}  // namespace

TEST(Georeferencing, SouthUpAndMirroredRastersLoadNorthUp) {
  tstest::TempDir tmp;
  const double north_up[6] = {500000, 10, 0, 5000020, 0, -10};
  const double south_up[6] = {500000, 10, 0, 5000000, 0, 10};    // row 0 is the south edge
  const double mirrored[6] = {500030, -10, 0, 5000020, 0, -10};  // column 0 is the east edge
  write_tif(tmp / "n.tif", 3, 2, 1, GDT_Int16, kNorthUp, north_up);
  write_tif(tmp / "s.tif", 3, 2, 1, GDT_Int16, std::vector<std::int16_t>{4, 5, 6, 1, 2, 3},
            south_up);
  write_tif(tmp / "m.tif", 3, 2, 1, GDT_Int16, std::vector<std::int16_t>{3, 2, 1, 6, 5, 4},
            mirrored);
  const Heightfield n = load_dem(dem(tmp / "n.tif"));
  for (const char* f : {"s.tif", "m.tif"}) {
    const Heightfield h = load_dem(dem(tmp / f));
    EXPECT_EQ(h.heights, n.heights) << f;
    ASSERT_TRUE(h.geo.has_value());
    for (int k = 0; k < 6; ++k) EXPECT_DOUBLE_EQ(h.geo->gt[k], north_up[k]) << f << " term " << k;
    EXPECT_DOUBLE_EQ(h.spacing_x, 10.0);
    EXPECT_DOUBLE_EQ(h.spacing_y, 10.0);
  }
}

TEST(Georeferencing, RotatedRasterIsRefused) {
  tstest::TempDir tmp;
  const double rotated[6] = {500000, 10, 2, 5000020, 2, -10};
  write_tif(tmp / "r.tif", 3, 2, 1, GDT_Int16, kNorthUp, rotated);
  try {
    load_dem(dem(tmp / "r.tif"));
    FAIL() << "a rotated raster loaded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("rotated"), std::string::npos) << e.what();
  }
}

TEST(Georeferencing, DrapeThatMissesTheHeightsIsRefusedOrWarned) {
  tstest::TempDir tmp;
  const double gt[6] = {500000, 10, 0, 5000040, 0, -10};
  write_tif(tmp / "d.tif", 5, 5, 1, GDT_Int16, std::vector<std::int16_t>(25, 100), gt);
  const std::vector<std::uint8_t> rgb(3 * 25, 200);
  const double far_away[6] = {900000, 10, 0, 5000040, 0, -10};
  write_tif(tmp / "far.tif", 5, 5, 3, GDT_Byte, rgb, far_away);
  // The south-east corner: 25 of the 40 m between sample centres each way, 39%.
  const double quarter[6] = {500020, 10, 0, 5000020, 0, -10};
  write_tif(tmp / "quarter.tif", 5, 5, 3, GDT_Byte, rgb, quarter);
  TerrainOptions o = dem(tmp / "d.tif");
  o.texture = tmp / "far.tif";
  EXPECT_THROW(load_terrain(o), InputError);
  o.texture = tmp / "quarter.tif";
  std::vector<std::string> warnings;
  load_terrain(o, &warnings);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("covers only 39%"), std::string::npos) << warnings[0];
  write_tif(tmp / "same.tif", 5, 5, 3, GDT_Byte, rgb, gt);
  o.texture = tmp / "same.tif";  // full overlap: no word
  warnings.clear();
  load_terrain(o, &warnings);
  EXPECT_TRUE(warnings.empty());
}

TEST(Georeferencing, TransparentTexelsShowTheDerivedTexture) {
  tstest::TempDir tmp;
  const double gt[6] = {500000, 10, 0, 5000040, 0, -10};
  std::vector<std::int16_t> heights(25);
  for (int p = 0; p < 25; ++p) heights[p] = std::int16_t(100 + 50 * (p % 5));
  write_tif(tmp / "d.tif", 5, 5, 1, GDT_Int16, heights, gt);
  std::vector<std::uint8_t> rgba(4 * 25, 0);  // black, and transparent on the left column
  for (int p = 0; p < 25; ++p) rgba[3 * 25 + p] = p % 5 == 0 ? 0 : 255;
  write_tif(tmp / "t.tif", 5, 5, 4, GDT_Byte, rgba, gt);
  TerrainOptions o = dem(tmp / "d.tif");
  o.texture = tmp / "t.tif";
  const Terrain t = load_terrain(o);
  for (int y = 0; y < 5; ++y) {
    const std::uint8_t* left = t.texture.px(0, y);
    EXPECT_EQ(left[3], 255);
    EXPECT_GT(left[0] + left[1] + left[2], 0) << "row " << y;  // derived colour, not black
    const std::uint8_t* right = t.texture.px(4, y);
    EXPECT_EQ(right[0] + right[1] + right[2], 0);  // the image's own texels untouched
  }
}

TEST(Georeferencing, ImplausibleTerrainRgbHeightsWarn) {
  tstest::TempDir tmp;
  // Mid-grey photo pixels decode to about 832 km.
  Image img(2, 2);
  for (std::size_t i = 0; i < img.rgba.size(); ++i) img.rgba[i] = 128;
  save_png(img, tmp / "photo.png");
  TerrainOptions o = dem(tmp / "photo.png");
  o.encoding = HeightEncoding::kTerrainRgb;
  std::vector<std::string> warnings;
  load_dem(o, &warnings);
  bool warned = false;
  for (const auto& w : warnings) warned |= w.find("outside -12 km .. +9 km") != std::string::npos;
  EXPECT_TRUE(warned);
}
