// SPDX-License-Identifier: MIT
// A table of hostile inputs, each run in a working directory full of the
// user's files: one line naming the input, exit status 2, nothing written and
// nothing removed (the directory's listing, sizes and times unchanged).
#include <gdal.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>

#include "hostile_row.h"
#include "test_util.h"

namespace fs = std::filesystem;

namespace {

struct Row {
  const char* args;      ///< CLI arguments, run in the work directory
  const char* fragment;  ///< the one line must contain this
};

// Fast terrain and render options, so a row that wrongly succeeded would still end quickly.
#define SMALL "--synthetic-size 33 "
#define RENDER "render " SMALL "--frames 1 --size 16x16 "

const Row kRows[] = {
    // Output locations that hold the user's data.
    {RENDER "--out .", "'.'"},
    {RENDER "--out ./", "'.'"},
    {RENDER "--out ..", "'..'"},
    {RENDER "--out mydata/..", "'..'"},
    {RENDER "--out mydata/deep/../..", "'..'"},
    {RENDER "--out /", "root"},
    {RENDER "--out afile", "afile: it exists and is not a directory"},
    {RENDER "--out /dev/null", "/dev/null: it exists and is not a directory"},
    {RENDER "--out mydata", "mydata: it exists and is not a terrasprite output"},
    {RENDER "--out link", "link: it is a symbolic link"},
    {RENDER "--out busy", "busy.partial already exists"},
    {RENDER "--out afile/sub", "afile/sub"},
    {"demo " SMALL "--frames 2 --size 16x16 --out mydata",
     "mydata: it exists and is not a terrasprite"},
    // Single-file outputs, checked before the work.
    {RENDER "--out o --json adir", "adir: is a directory"},
    {RENDER "--out o --json /proc/x/y.json", "/proc/x/y.json"},
    {RENDER "--out o --json theirs.json", "theirs.json: exists and was not written by terrasprite"},
    {RENDER "--out o --json nosuchdir/s.json",
     "nosuchdir/s.json: directory nosuchdir does not exist"},
    {"info " SMALL "--json /dev/null", "/dev/null: is a device"},
    {"info " SMALL "--json theirs.json", "theirs.json: exists and was not written"},
    {"compare img.png img.png --diff afile", "afile: exists and was not written"},
    {"bench render " SMALL "--frames 1 --size 16x16 --json adir", "adir: is a directory"},
    // Camera path files.
    {RENDER "--out o --path huge.json", "coordinates must be finite and within"},
    {RENDER "--out o --path overflow.json", "overflow.json: unreadable JSON"},
    {RENDER "--out o --path truncated.json", "truncated.json: malformed JSON"},
    {RENDER "--out o --path hugetime.json", ".t 1e+300: must be finite"},
    {RENDER "--out o --path backwards.json", ".t must be greater than the previous"},
    {RENDER "--out o --path nokeys.json", "needs a non-empty \"keyframes\" array"},
    {RENDER "--out o --path fov.json", "fov_deg must be in (0, 180)"},
    {RENDER "--out o --path same.json", "target equals its position"},
    {RENDER "--out o --path pitch.json", "pitch_deg must be in [-90, 90]"},
    {RENDER "--out o --path textpos.json", "position must be an array of 3 numbers"},
    {RENDER "--out o --path adir", "adir: no such path file"},
    // Sizes, counts and work bounds.
    {"render " SMALL "--frames 1 --out o --size 4294967360x64", "--size 4294967360x64"},
    {"render " SMALL "--frames 1 --out o --size 64x-4294967232", "--size 64x-4294967232"},
    {"render " SMALL "--frames 1 --out o --size 16x", "--size 16x"},
    {"render " SMALL "--frames 0 --size 16x16 --out o", "--frames 0"},
    {"bench render " SMALL "--frames 2147483647 --size 16x16",
     "--frames: Value 2147483647 not in range"},
    // Input files that are directories.
    {"view --script mydata", "mydata: is a directory, not a script file"},
    {"objects scene --scene mydata", "mydata: is a directory, not a scene file"},
    {"render " SMALL "--frames 4294967297 --size 16x16 --out o", "--frames"},
    {"info --erosion -1", "--erosion -1"},
    {"info --erosion 1000000", "--erosion 1000000"},
    {"info --synthetic-size 16385", "--synthetic-size 16385"},
    {"info --synthetic-size 1", "--synthetic-size 1"},
    {"info " SMALL "--resample 1", "--resample 1"},
    {"info " SMALL "--exaggeration 0", "--exaggeration 0"},
    {RENDER "--out o --mode lod --lod-quads 0", "--lod-quads 0"},
    {RENDER "--out o --mode lod --lod-quads 100000",
     "--lod-quads 100000: must be between 1 and 32"},
    {RENDER "--out o --mode sprite --lod-quads 100000", "--lod-quads 100000"},
    {"bench render " SMALL "--frames 1 --size 16x16 --lod-quads 0", "--lod-quads 0"},
    {"bench voxel " SMALL "--frames 1 --size 16x16 --threads 999 --out o", "--threads 999"},
    {"bench voxel " SMALL "--frames 1 --size 16x16 --terrain-sizes 8194 --out o",
     "--terrain-sizes 8194: sizes must be whole, 2..8193"},
    // Heights that are not finite after scaling, degenerate spacing.
    {"info --dem small.asc --z-scale 1e300", "after scale, offset and --z-scale is not a finite"},
    {"info --dem small.asc --z-scale nan", "--z-scale: nan"},
    {"info --dem small.asc --spacing 1e-300", "--spacing 1e-300"},
    {"info --dem tinycell.asc", "sample spacing"},
    {"info --dem float64.tif", "float64.tif: height"},
    {"info --dem nanscale.tif", "nanscale.tif: height"},
    {"info --dem hugescale.tif", "hugescale.tif: height"},
    // Files that are not what they claim.
    {"info --dem ''", "--dem \"\": empty file name"},
    {"info --dem nosuch.tif", "nosuch.tif: no such file"},
    {"info --dem junk.tif", "junk.tif: not a readable height raster"},
    {"info --dem adir", "adir: is a directory"},
    {"info --dem allvoid.asc", "all cells are nodata"},
    {"info --dem small.asc --encoding terrain-rgb", "--encoding needs an 8-bit RGB raster"},
    {"info " SMALL "--texture nosuch.png", "nosuch.png: no such file"},
    {"info " SMALL "--texture junk.tif", "junk.tif: not a readable image"},
    {"compare img.png nosuch.png", "nosuch.png: no such file"},
    {"compare img.png small.asc --ppd 0", "--ppd 0"},
    // Floating options are finite; whole numbers are never wrapped.
    {"bench replay-controller . --tolerance nan", "--tolerance: nan is not a finite number"},
    {"bench hybrid --p95-aim nan", "--p95-aim: nan is not a finite number"},
    {"bench hybrid --cull-px nan", "--cull-px: nan is not a finite number"},
    {RENDER "--out o --frame-range 4294967297:4294967298", "--frame-range 4294967297:4294967298"},
    {"bench voxel " SMALL "--frames 1 --size 16x16 --terrain-sizes 4294967297 --out o",
     "--terrain-sizes"},
    // Usage.
    {"render --no-such-option", "--no-such-option"},
    {"info --nodata abc", "--nodata"},
};

void write_file(const fs::path& p, const std::string& text) {
  std::ofstream(p) << text;
}

std::string path_json(const std::string& keyframes) {
  return "{\"keyframes\": [" + keyframes + "]}";
}

// A single-band GeoTIFF of `type` with every sample `value`, `scale` as band scale.
void write_tif(const fs::path& p, GDALDataType type, double value, double scale) {
  GDALAllRegister();
  GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), p.c_str(), 4, 4, 1, type, nullptr);
  ASSERT_NE(ds, nullptr);
  double gt[6] = {500000, 30, 0, 4000000, 0, -30};
  GDALSetGeoTransform(ds, gt);
  GDALRasterBandH b = GDALGetRasterBand(ds, 1);
  std::vector<double> v(16, 100.0);
  v[5] = value;
  ASSERT_EQ(GDALRasterIO(b, GF_Write, 0, 0, 4, 4, v.data(), 4, 4, GDT_Float64, 0, 0), CE_None);
  GDALSetRasterScale(b, scale);
  GDALClose(ds);
}

void write_png(const fs::path& p) {
  GDALAllRegister();
  GDALDatasetH mem = GDALCreate(GDALGetDriverByName("MEM"), "", 8, 8, 3, GDT_Byte, nullptr);
  GDALDatasetH png =
      GDALCreateCopy(GDALGetDriverByName("PNG"), p.c_str(), mem, FALSE, nullptr, nullptr, nullptr);
  GDALClose(png);
  GDALClose(mem);
  std::error_code ec;
  fs::remove(p.string() + ".aux.xml", ec);
}

// The user's working directory: files of theirs, and every hostile input.
void make_fixtures(const fs::path& w) {
  fs::create_directories(w / "mydata" / "deep");
  write_file(w / "mydata" / "precious.txt", "mine");
  write_file(w / "mydata" / "deep" / "thesis.tex", "also mine");
  write_file(w / "afile", "a file of mine");
  write_file(w / "theirs.json", "{\"mine\": true}\n");
  fs::create_directory(w / "adir");
  fs::create_directory(w / "busy.partial");
  write_file(w / "busy.partial" / "in-progress.png", "another run's");
  fs::create_directory_symlink(w / "mydata", w / "link");
  write_file(w / "junk.tif", "this is not a raster");
  write_png(w / "img.png");
  const std::string key1 = R"({"t": 0, "position": [-3000, -3000, 2000], "target": [0, 0, 0]})";
  write_file(w / "huge.json",
             path_json(R"({"t": 0, "position": [1e308, 0, 2000], "target": [0, 0, 0]})"));
  write_file(w / "overflow.json",
             path_json(R"({"t": 0, "position": [1e999, 0, 2000], "target": [0, 0, 0]})"));
  write_file(w / "truncated.json", "{\"keyframes\": [{\"t\": 0, \"posi");
  write_file(w / "hugetime.json",
             path_json(R"({"t": 1e300, "position": [0, 0, 2000], "target": [0, 0, 0]})"));
  write_file(w / "backwards.json",
             path_json(key1 + R"(, {"t": -1, "position": [0, 0, 2000], "target": [0, 0, 0]})"));
  write_file(w / "nokeys.json", "{\"keyframes\": []}");
  write_file(w / "fov.json",
             path_json(R"({"t": 0, "position": [0, 0, 2000], "target": [0, 0, 0], "fov_deg": 0})"));
  write_file(w / "same.json", path_json(R"({"t": 0, "position": [0, 0, 0], "target": [0, 0, 0]})"));
  write_file(w / "pitch.json",
             path_json(R"({"t": 0, "position": [0, 0, 2000], "yaw_deg": 0, "pitch_deg": 100})"));
  write_file(w / "textpos.json", path_json(R"({"t": 0, "position": "here", "target": [0, 0, 0]})"));
  write_file(w / "small.asc",
             "ncols 3\nnrows 3\nxllcorner 0\nyllcorner 0\ncellsize 30\n1 2 3\n4 5 6\n7 8 9\n");
  write_file(w / "tinycell.asc",
             "ncols 3\nnrows 3\nxllcorner 0\nyllcorner 0\ncellsize 1e-30\n1 2 3\n4 5 6\n7 8 9\n");
  write_file(w / "allvoid.asc",
             "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 30\nNODATA_value -9999\n"
             "-9999 -9999\n-9999 -9999\n");
  write_tif(w / "float64.tif", GDT_Float64, 1e308, 1.0);
  write_tif(w / "nanscale.tif", GDT_Int16, 100, std::nan(""));
  write_tif(w / "hugescale.tif", GDT_Int16, 100, 1e300);
}

using tstest::snapshot;

}  // namespace

TEST(HostileInputs, EachFailsInOneLineAndTouchesNothing) {
  tstest::TempDir tmp;
  const fs::path work = tmp.path / "work";
  fs::create_directory(work);
  make_fixtures(work);
  const auto before = snapshot(work);
  ASSERT_GE(std::size(kRows), 40u);
  for (const Row& row : kRows) {
    tstest::expect_refused_untouched(work, row.args, row.fragment, before);
  }
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
}
