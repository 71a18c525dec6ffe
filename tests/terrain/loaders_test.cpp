// SPDX-License-Identifier: MIT
// Height loaders: files written here and read back, encodings, nodata, and
// each real data set in ../shared/data.
#include <cpl_conv.h>
#include <gdal.h>
#include <gtest/gtest.h>
#include <ogr_srs_api.h>

#include <cmath>
#include <fstream>

#include "terrasprite/terrain/image_io.h"
#include "terrasprite/common/error.h"
#include "terrasprite/terrain/terrain.h"
#include "terrasprite/terrain/dem_loader.h"
#include "terrasprite/terrain/resample.h"
#include "terrasprite/terrain/synth.h"
#include "test_util.h"

using namespace terrasprite;

namespace {

// Writes a single-band Int16 GeoTIFF with a geotransform, CRS (EPSG code or none) and nodata.
void write_geotiff(const std::string& path, int w, int h, const std::vector<std::int16_t>& v,
                   const double gt[6], int epsg, const double* nodata) {
  GDALAllRegister();
  GDALDatasetH ds =
      GDALCreate(GDALGetDriverByName("GTiff"), path.c_str(), w, h, 1, GDT_Int16, nullptr);
  ASSERT_NE(ds, nullptr);
  GDALSetGeoTransform(ds, const_cast<double*>(gt));
  if (epsg) {
    OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
    OSRImportFromEPSG(srs, epsg);
    char* wkt = nullptr;
    OSRExportToWkt(srs, &wkt);
    GDALSetProjection(ds, wkt);
    CPLFree(wkt);
    OSRDestroySpatialReference(srs);
  }
  GDALRasterBandH b = GDALGetRasterBand(ds, 1);
  if (nodata) GDALSetRasterNoDataValue(b, *nodata);
  ASSERT_EQ(GDALRasterIO(b, GF_Write, 0, 0, w, h, const_cast<std::int16_t*>(v.data()), w, h,
                         GDT_Int16, 0, 0),
            CE_None);
  GDALClose(ds);
}

TerrainOptions dem(const std::string& path) {
  TerrainOptions o;
  o.dem = path;
  return o;
}

}  // namespace

TEST(Loaders, ProjectedGeoTiffValuesSpacingAndNodata) {
  tstest::TempDir tmp;
  std::vector<std::int16_t> v = {10, 20, 30, 40, -9999, 60, 70, 80, 90, 100, 110, 120};
  const double gt[6] = {500000, 25, 0, 5000000, 0, -25};  // UTM, 25 m pixels
  const double nodata = -9999;
  write_geotiff(tmp / "a.tif", 4, 3, v, gt, 32633, &nodata);
  Heightfield h = load_dem(dem(tmp / "a.tif"));
  EXPECT_EQ(h.width, 4);
  EXPECT_EQ(h.height, 3);
  EXPECT_DOUBLE_EQ(h.spacing_x, 25.0);
  EXPECT_DOUBLE_EQ(h.spacing_y, 25.0);
  EXPECT_EQ(h.nodata_count, 1);
  EXPECT_FLOAT_EQ(h.at(0, 0), 10.f);
  EXPECT_FLOAT_EQ(h.at(3, 2), 120.f);
  // The hole is filled from its neighbours, never left at the sentinel.
  EXPECT_GT(h.at(0, 1), 10.f);
  EXPECT_LT(h.at(0, 1), 110.f);
  EXPECT_FLOAT_EQ(h.min_height(), 10.f);
}

TEST(Loaders, GeographicDegreesBecomeMetresAtCentreLatitude) {
  tstest::TempDir tmp;
  std::vector<std::int16_t> v(9, 5);
  const double gt[6] = {10.0, 0.001, 0, 60.0015, 0, -0.001};  // centred near 60 N
  write_geotiff(tmp / "g.tif", 3, 3, v, gt, 4326, nullptr);
  Heightfield h = load_dem(dem(tmp / "g.tif"));
  // At 60 degrees a degree of longitude is about half a degree of latitude.
  EXPECT_NEAR(h.spacing_y, 111.41, 0.2);
  EXPECT_NEAR(h.spacing_x, 55.8, 0.2);
}

TEST(Loaders, UntaggedSentinelWarnsAndNodataOptionFills) {
  tstest::TempDir tmp;
  std::vector<std::int16_t> v(100, 300);
  for (int i = 0; i < 10; ++i) v[i] = -32767;
  const double gt[6] = {0, 30, 0, 3000, 0, -30};
  write_geotiff(tmp / "s.tif", 10, 10, v, gt, 32633, nullptr);
  std::vector<std::string> warnings;
  Heightfield raw = load_dem(dem(tmp / "s.tif"), &warnings);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("-32767"), std::string::npos);
  EXPECT_FLOAT_EQ(raw.min_height(), -32767.f);
  TerrainOptions o = dem(tmp / "s.tif");
  o.nodata = -32767;
  Heightfield filled = load_dem(o);
  EXPECT_EQ(filled.nodata_count, 10);
  EXPECT_FLOAT_EQ(filled.min_height(), 300.f);
}

TEST(Loaders, AllNodataIsAnError) {
  tstest::TempDir tmp;
  std::vector<std::int16_t> v(16, -32768);
  const double gt[6] = {0, 30, 0, 3000, 0, -30};
  const double nodata = -32768;
  write_geotiff(tmp / "n.tif", 4, 4, v, gt, 32633, &nodata);
  try {
    load_dem(dem(tmp / "n.tif"));
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("all cells are nodata"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("n.tif"), std::string::npos);
  }
}

TEST(Loaders, Png16WithZScaleAndSpacing) {
  tstest::TempDir tmp;
  std::vector<std::uint16_t> v = {0, 1000, 2000, 3000, 4000, 5000};
  save_png16(v, 3, 2, tmp / "h.png");
  TerrainOptions o = dem(tmp / "h.png");
  o.z_scale = 0.1;
  o.spacing = 160;
  Heightfield h = load_dem(o);
  EXPECT_EQ(h.width, 3);
  EXPECT_EQ(h.height, 2);
  EXPECT_DOUBLE_EQ(h.spacing_x, 160.0);
  EXPECT_NEAR(h.at(1, 0), 100.0, 1e-4);
  EXPECT_NEAR(h.at(2, 1), 500.0, 1e-4);
}

TEST(Loaders, SrtmHgtBigEndianWithVoids) {
  tstest::TempDir tmp;
  const int n = 1201;
  std::vector<unsigned char> bytes(n * n * 2);
  for (int p = 0; p < n * n; ++p) {
    std::int16_t v = p == 5 ? std::int16_t(-32768) : std::int16_t(p % 1000);
    bytes[2 * p] = std::uint8_t((v >> 8) & 0xff);
    bytes[2 * p + 1] = std::uint8_t(v & 0xff);
  }
  std::ofstream(tmp / "N45E007.hgt", std::ios::binary)
      .write(reinterpret_cast<char*>(bytes.data()), bytes.size());
  Heightfield h = load_dem(dem(tmp / "N45E007.hgt"));
  EXPECT_EQ(h.width, n);
  EXPECT_EQ(h.nodata_count, 1);
  EXPECT_FLOAT_EQ(h.at(7, 0), 7.f);
  EXPECT_NEAR(h.spacing_y, 92.6, 0.3);  // 3 arc-seconds of latitude
}

TEST(Loaders, TerrainRgbAndTerrariumDecoding) {
  EXPECT_DOUBLE_EQ(decode_terrain_rgb(1, 134, 160), -10000.0 + (65536 + 134 * 256 + 160) * 0.1);
  EXPECT_NEAR(decode_terrain_rgb(1, 134, 160), 0.0, 1e-9);  // sea level in Mapbox's encoding
  EXPECT_DOUBLE_EQ(decode_terrarium(128, 0, 0), 0.0);
  EXPECT_DOUBLE_EQ(decode_terrarium(128, 100, 128), 100.5);
}

TEST(Loaders, EncodedRgbPngReadsAsHeights) {
  tstest::TempDir tmp;
  Image img(2, 1);
  const std::uint8_t px[2][3] = {{1, 134, 160}, {1, 138, 136}};
  for (int x = 0; x < 2; ++x)
    for (int c = 0; c < 3; ++c) img.px(x, 0)[c] = px[x][c];
  img.px(0, 0)[3] = img.px(1, 0)[3] = 255;
  Image tall(2, 2);
  tall.rgba.assign(img.rgba.begin(), img.rgba.end());
  tall.rgba.insert(tall.rgba.end(), img.rgba.begin(), img.rgba.end());
  save_png(tall, tmp / "rgb.png");
  TerrainOptions o = dem(tmp / "rgb.png");
  EXPECT_THROW(load_dem(o), InputError);  // colour raster without --encoding
  o.encoding = HeightEncoding::kTerrainRgb;
  Heightfield h = load_dem(o);
  EXPECT_NEAR(h.at(0, 0), 0.0, 1e-3);
  EXPECT_NEAR(h.at(1, 1), decode_terrain_rgb(1, 138, 136), 1e-3);
}

TEST(Loaders, ResampleKeepsExtentAndCorners) {
  SynthOptions s;
  s.size = 65;
  Heightfield h = synthesize_terrain(s);
  Heightfield r = resample_heightfield(h, 33, 33);
  EXPECT_DOUBLE_EQ(r.extent_x(), h.extent_x());
  EXPECT_FLOAT_EQ(r.at(0, 0), h.at(0, 0));
  EXPECT_FLOAT_EQ(r.at(32, 32), h.at(64, 64));
  EXPECT_FLOAT_EQ(r.at(16, 16), h.at(32, 32));
  ASSERT_TRUE(r.resampled_to.has_value());
}

TEST(Loaders, GeoregisteredTextureRectangle) {
  tstest::TempDir tmp;
  std::vector<std::int16_t> v(16, 100);
  const double gt[6] = {500000, 10, 0, 5000000, 0, -10};
  write_geotiff(tmp / "d.tif", 4, 4, v, gt, 32633, nullptr);
  // A texture twice as wide, same origin, 10 m pixels: the DEM covers its left half.
  GDALDatasetH ds =
      GDALCreate(GDALGetDriverByName("GTiff"), (tmp / "t.tif").c_str(), 8, 4, 3, GDT_Byte, nullptr);
  GDALSetGeoTransform(ds, const_cast<double*>(gt));
  OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
  OSRImportFromEPSG(srs, 32633);
  char* wkt = nullptr;
  OSRExportToWkt(srs, &wkt);
  GDALSetProjection(ds, wkt);
  CPLFree(wkt);
  OSRDestroySpatialReference(srs);
  GDALClose(ds);
  TerrainOptions o = dem(tmp / "d.tif");
  o.texture = tmp / "t.tif";
  Terrain t = load_terrain(o);
  // Sample centres 0.5 .. 3.5 pixels of an 8-pixel-wide texture.
  EXPECT_NEAR(t.tex_rect[0], 0.5 / 8, 1e-12);
  EXPECT_NEAR(t.tex_rect[2], 3.0 / 8, 1e-12);
  EXPECT_NEAR(t.tex_rect[1], 0.5 / 4, 1e-12);
  EXPECT_NEAR(t.tex_rect[3], 3.0 / 4, 1e-12);
}

TEST(RealData, EachSharedDatasetLoads) {
  const std::string d = tstest::shared_data();
  if (d.empty()) GTEST_SKIP() << "../shared/data is absent; real-data checks skipped";
  struct Case {
    std::string file;
    double z_scale, spacing, nodata;
    int w, h;
    float lo, hi;
  };
  const double none = std::nan("");
  const Case cases[] = {
      {"/puget_sound_1k/ps_height_1k.png", 0.1, 160, none, 1025, 1025, -1, 4400},
      {"/crater_lake_bathymetry/craterlake-elev-16bit-30m.tif", 1, none, -32767, 429, 279, 1200,
       1900},
      {"/srtm3_n00e010_gabon/N00E010.hgt", 1, none, none, 1201, 1201, -50, 1100},
      {"/srtm3_mt_fuji/mt_fuji_90m.tif", 1, none, none, 1201, 1201, -100, 3800},
  };
  for (const Case& c : cases) {
    TerrainOptions o = dem(d + c.file);
    o.z_scale = c.z_scale;
    if (!std::isnan(c.spacing)) o.spacing = c.spacing;
    if (!std::isnan(c.nodata)) o.nodata = c.nodata;
    Heightfield h = load_dem(o);
    EXPECT_EQ(h.width, c.w) << c.file;
    EXPECT_EQ(h.height, c.h) << c.file;
    EXPECT_GE(h.min_height(), c.lo) << c.file;
    EXPECT_LE(h.max_height(), c.hi) << c.file;
    EXPECT_GT(h.max_height(), h.min_height() + 100) << c.file;
  }
  // Crater Lake's texture is georeferenced on the same grid: texel centres on samples.
  TerrainOptions o = dem(d + "/crater_lake_bathymetry/craterlake-elev-16bit-30m.tif");
  o.nodata = -32767;
  o.texture = d + "/crater_lake_bathymetry/craterlake-imagery-30m.tif";
  Terrain t = load_terrain(o);
  EXPECT_NEAR(t.tex_rect[0], 0.5 / 429, 1e-9);
  EXPECT_NEAR(t.tex_rect[2], 428.0 / 429, 1e-9);
}
