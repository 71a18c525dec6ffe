// SPDX-License-Identifier: MIT
// Writes the fuzz targets' seed inputs: small crops of the real rasters in
// ../shared/data (each format and encoding we read) and crafted cases.
// Build and run: make fuzz-seeds (seeds go to build-fuzz/seeds/<target>/).
#include <gdal.h>
#include <cpl_conv.h>
#include <cpl_string.h>
#include <gdal_utils.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

// A window of `src` (clamped) written with `driver` to `dst`.
void crop(const std::string& src, const std::string& dst, const char* driver, int x, int y,
          int size) {
  GDALDatasetH in = GDALOpen(src.c_str(), GA_ReadOnly);
  if (!in) return void(std::fprintf(stderr, "skip %s\n", src.c_str()));
  char** args = nullptr;
  args = CSLAddString(args, "-srcwin");
  for (int v : {x, y, size, size}) args = CSLAddString(args, std::to_string(v).c_str());
  args = CSLAddString(args, "-of");
  args = CSLAddString(args, driver);
  GDALTranslateOptions* o = GDALTranslateOptionsNew(args, nullptr);
  GDALDatasetH out = GDALTranslate(dst.c_str(), in, o, nullptr);
  if (out) GDALClose(out);
  GDALTranslateOptionsFree(o);
  CSLDestroy(args);
  GDALClose(in);
  std::error_code ec;
  fs::remove(dst + ".aux.xml", ec);
}

// A `w` x `h` raster of `bands` bands from `pixels` (band-sequential).
template <class T>
void write(const std::string& dst, const char* driver, int w, int h, int bands, GDALDataType type,
           const std::vector<T>& pixels, const double* gt) {
  GDALDatasetH mem = GDALCreate(GDALGetDriverByName("MEM"), "", w, h, bands, type, nullptr);
  if (gt) GDALSetGeoTransform(mem, const_cast<double*>(gt));
  (void)GDALDatasetRasterIO(mem, GF_Write, 0, 0, w, h, const_cast<T*>(pixels.data()), w, h, type,
                            bands, nullptr, 0, 0, 0);
  GDALDatasetH out = GDALCreateCopy(GDALGetDriverByName(driver), dst.c_str(), mem, FALSE, nullptr,
                                    nullptr, nullptr);
  if (out) GDALClose(out);
  GDALClose(mem);
  std::error_code ec;
  fs::remove(dst + ".aux.xml", ec);
}

// The PNG target's first byte selects the reader (fuzz_png16.cpp).
void prefix(const std::string& file, char mode, const std::string& dst) {
  std::ifstream in(file, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), {});
  std::ofstream(dst, std::ios::binary) << mode << bytes;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string data = argc > 1 ? argv[1] : "../shared/data",
                    out = argc > 2 ? argv[2] : "seeds";
  GDALAllRegister();
  for (const char* d : {"dem", "png16", "path", "tmp"}) fs::create_directories(fs::path(out) / d);
  const std::string dem = out + "/dem/", png = out + "/png16/", tmp = out + "/tmp/";
  crop(data + "/srtm3_mt_fuji/mt_fuji_90m.tif", dem + "fuji.tif", "GTiff", 300, 300, 24);
  crop(data + "/crater_lake_bathymetry/craterlake-elev-16bit-30m.tif", dem + "crater.tif", "GTiff",
       0, 0, 24);
  crop(data + "/srtm3_n00e010_gabon/N00E010.hgt", dem + "gabon.asc", "AAIGrid", 500, 500, 12);
  crop(data + "/srtm3_n00e010_gabon/N00E010.hgt", dem + "gabon.tif", "GTiff", 500, 500, 16);
  crop(data + "/puget_sound_1k/ps_height_1k.png", tmp + "ps16.png", "PNG", 400, 400, 24);
  crop(data + "/puget_sound_1k/ps_texture_1k.png", tmp + "pstex.png", "PNG", 400, 400, 16);
  crop(data + "/crater_lake_bathymetry/craterlake-imagery-30m.tif", dem + "crater_rgba.tif",
       "GTiff", 0, 0, 16);
  // Terrain-RGB and Terrarium encodings of a slope, and a south-up raster.
  std::vector<std::uint8_t> rgb(3 * 16 * 16);
  for (int p = 0; p < 256; ++p) {
    const unsigned v = unsigned((1000 + p * 3 + 10000) * 10);  // terrain-RGB: (h + 10000) / 0.1
    rgb[p] = std::uint8_t(v >> 16), rgb[256 + p] = std::uint8_t(v >> 8),
    rgb[512 + p] = std::uint8_t(v);
  }
  write(tmp + "terrainrgb.png", "PNG", 16, 16, 3, GDT_Byte, rgb, nullptr);
  const double south_up[6] = {138.0, 0.001, 0, 35.0, 0, 0.001};
  std::vector<std::int16_t> hs(64);
  for (int p = 0; p < 64; ++p) hs[p] = std::int16_t(p * 10 - (p == 9 ? 32768 + 90 : 0));
  write(dem + "south_up.tif", "GTiff", 8, 8, 1, GDT_Int16, hs, south_up);
  write(dem + "plain.asc", "AAIGrid", 8, 8, 1, GDT_Int16, hs, south_up);
  prefix(tmp + "ps16.png", 0, png + "ps16");
  prefix(tmp + "terrainrgb.png", 1, png + "terrainrgb");
  prefix(tmp + "terrainrgb.png", 2, png + "terrarium");
  prefix(tmp + "pstex.png", 3, png + "texture");
  fs::remove_all(tmp);
  fs::remove(dem + "gabon.prj");
  std::ofstream(out + "/path/example.json")
      << R"({"keyframes": [{"t": 0, "position": [-6000, -6000, 3500], "target": [0, 0, 800], "fov_deg": 60},
{"t": 8, "position": [4000, -1000, 2400], "yaw_deg": -30, "pitch_deg": -12, "roll_deg": -8}]})";
  std::ofstream(out + "/path/one.json")
      << R"({"keyframes": [{"t": 0, "position": [0, 0, 900], "yaw_deg": 0, "pitch_deg": -90}]})";
  std::ofstream(out + "/path/huge.json")
      << R"({"keyframes": [{"t": 0, "position": [1e308, 0, 0], "target": [0, 0, 0]}]})";
  std::ofstream(out + "/path/overflow.json")
      << R"({"keyframes": [{"t": 1e999, "position": [0, 0, 1], "target": [0, 0, 0]}]})";
  return 0;
}
