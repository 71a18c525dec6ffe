// SPDX-License-Identifier: MIT
#include "stream/tile_set_json.h"

#include <fmt/format.h>
#include <gdal_priv.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "terrain/gdal_util.h"
#include "terrasprite/common/error.h"
#include "terrasprite/common/input_file.h"
#include "terrasprite/terrain/terrain.h"

namespace terrasprite {
namespace {

constexpr const char* kFormat = "terrasprite-tiles";
constexpr int kVersion = 1;

// Opens `path` and checks its size and overview count; throws InputError.
void check_raster(const std::string& path, int w, int h, int overviews, int bands) {
  detail::GdalErrorCapture capture;
  GDALDatasetH ds =
      GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr);
  if (!ds) throw InputError(fmt::format("{}: cannot open: {}", path, capture.last()));
  const int rw = GDALGetRasterXSize(ds), rh = GDALGetRasterYSize(ds), rb = GDALGetRasterCount(ds);
  const int ro = rb > 0 ? GDALGetOverviewCount(GDALGetRasterBand(ds, 1)) : 0;
  GDALClose(ds);
  if (rw != w || rh != h || rb < bands || ro != overviews)
    throw InputError(fmt::format(
        "{}: {}x{} with {} bands and {} overviews; tiles.json says {}x{}, {} bands, {} overviews",
        path, rw, rh, rb, ro, w, h, bands, overviews));
}

}  // namespace

int TileSetInfo::tiles_cells_w(int level) const {
  return TerrainGrid::bound_cells(grid.width, level);
}
int TileSetInfo::tiles_cells_h(int level) const {
  return TerrainGrid::bound_cells(grid.height, level);
}

std::vector<std::vector<float>> tile_maxima(const TerrainGrid& g,
                                            const std::vector<const float*>& bounds,
                                            int tile_log2) {
  std::vector<std::vector<float>> out;
  const int T = 1 << tile_log2;
  for (int L = 0; L < g.bound_levels; ++L) {
    const int cw = TerrainGrid::bound_cells(g.width, L), ch = TerrainGrid::bound_cells(g.height, L);
    const int nx = (cw + T - 1) / T, ny = (ch + T - 1) / T;
    std::vector<float> maxes;
    maxes.reserve(std::size_t(nx) * ny);
    // The in-memory pyramid's own tiles are 2^7 cells; recompute per tile of T.
    const float* bound = bounds[std::size_t(L)];
    for (int ty = 0; ty < ny; ++ty)
      for (int tx = 0; tx < nx; ++tx) {
        float m = -std::numeric_limits<float>::infinity();
        for (int b = ty * T; b < std::min(ch, (ty + 1) * T); ++b)
          for (int a = tx * T; a < std::min(cw, (tx + 1) * T); ++a)
            m = std::max(m, bound[std::size_t(b) * std::size_t(cw) + std::size_t(a)]);
        maxes.push_back(m);
      }
    out.push_back(std::move(maxes));
  }
  return out;
}

void write_tile_set_json(const TerrainGrid& g, const std::vector<std::vector<float>>& tile_max,
                         const std::optional<GeoTransform>& geo, const TileWriteOptions& o,
                         const std::string& path) {
  nlohmann::json j;
  j["format"] = kFormat;
  j["version"] = kVersion;
  j["samples"] = {g.width, g.height};
  j["spacing_m"] = {g.spacing_x, g.spacing_y};
  j["extent_m"] = {g.spacing_x * (g.width - 1), g.spacing_y * (g.height - 1)};
  j["height_min"] = g.min_height;
  j["height_max"] = g.max_height;
  j["tile_cells"] = 1 << o.tile_log2;
  j["coarsest_level"] = g.coarsest_level;
  j["bound_levels"] = g.bound_levels;
  j["color_compress"] = o.color_compress;
  j["height_compress"] = o.height_compress;
  j["files"] = {{"height", "height.tif"}, {"color", "color.tif"}, {"bound", "bound.tif"}};
  if (geo) {
    j["geotransform"] = std::vector<double>(geo->gt, geo->gt + 6);
    j["srs_wkt"] = geo->wkt;
  }
  nlohmann::json insets = nlohmann::json::array();
  for (const InsetResult& r : o.insets)
    insets.push_back({{"file", r.path},
                      {"blend_samples", r.blend},
                      {"samples_replaced", r.samples_replaced},
                      {"samples_full", r.samples_full},
                      {"pixel_size", {r.spacing_m[0], r.spacing_m[1]}}});
  j["insets"] = insets;
  if (o.fine) {
    nlohmann::json present = nlohmann::json::array();
    for (const auto& lv : o.fine->present) {
      std::string bits(lv.size(), '0');
      for (std::size_t i = 0; i < lv.size(); ++i) bits[i] = lv[i] ? '1' : '0';
      present.push_back(bits);
    }
    j["fine"] = {{"dir", "fine"},
                 {"levels", o.fine->levels},
                 {"origin", {o.fine->origin_x, o.fine->origin_y}},
                 {"present", present}};
  }
  nlohmann::json levels = nlohmann::json::array();
  const int T = 1 << o.tile_log2;
  for (int L = 0; L < g.bound_levels; ++L) {
    const int cw = TerrainGrid::bound_cells(g.width, L), ch = TerrainGrid::bound_cells(g.height, L);
    const int nx = (cw + T - 1) / T, ny = (ch + T - 1) / T;
    levels.push_back({{"level", L},
                      {"samples", {cw + 1, ch + 1}},
                      {"has_samples", L <= g.coarsest_level},
                      {"tiles", {nx, ny}},
                      {"tile_max_height", tile_max[std::size_t(L)]}});
  }
  j["levels"] = levels;
  std::ofstream f(path);
  f << j.dump(1) << '\n';
  f.close();  // a write the buffer held fails here (a full disk, a file-size limit)
  if (!f) throw InputError(fmt::format("{}: cannot write", path));
}

namespace {

// Largest side of a tile set's level 0: keeps every sample index and count
// within 32 bits, with a margin of 32x over the largest set tile writes (2^15 + 1).
constexpr int kMaxTileSetSide = (1 << 20) + 1;

// A whole number of tiles.json within [lo, hi] (a float or a huge integer is
// refused before any conversion).
long long whole(const nlohmann::json& v, const std::string& path, const char* what, long long lo,
                long long hi) {
  if (!v.is_number_integer() ||
      (v.is_number_unsigned() && v.get<unsigned long long>() > (unsigned long long)hi))
    throw InputError(fmt::format("{}: {} must be a whole number in {} .. {}", path, what, lo, hi));
  const long long x = v.get<long long>();
  if (x < lo || x > hi)
    throw InputError(
        fmt::format("{}: {} {} must be a whole number in {} .. {}", path, what, x, lo, hi));
  return x;
}

// The level-0 grid of tiles.json, checked: sizes, spacing, height range, tiles.
void parse_grid(const nlohmann::json& j, const std::string& path, TerrainGrid& g) {
  g.width = int(whole(j.at("samples").at(0), path, "samples[0]", 2, kMaxTileSetSide));
  g.height = int(whole(j.at("samples").at(1), path, "samples[1]", 2, kMaxTileSetSide));
  g.spacing_x = j.at("spacing_m")[0];
  g.spacing_y = j.at("spacing_m")[1];
  check_spacing(path, g.spacing_x, g.spacing_y);
  g.min_height = j.at("height_min");
  g.max_height = j.at("height_max");
  check_height_range(path, g.min_height, g.max_height);
  g.finest_level = 0;
  g.coarsest_level = int(whole(j.at("coarsest_level"), path, "coarsest_level", 0, 30));
  g.bound_levels = int(whole(j.at("bound_levels"), path, "bound_levels", 1, 31));
  const int T = int(whole(j.at("tile_cells"), path, "tile_cells", 2, 1 << 10));
  g.tile_log2 = 0;
  while (g.tile_log2 < 10 && (1 << g.tile_log2) < T) ++g.tile_log2;
  if ((1 << g.tile_log2) != T || g.tile_log2 < 1 || g.bound_levels < 1 || g.bound_levels > 31 ||
      g.coarsest_level < 0 || g.coarsest_level >= g.bound_levels ||
      int(j.at("levels").size()) != g.bound_levels)
    throw InputError(fmt::format("{}: inconsistent grid or levels", path));
}

// Each level's tile table: exactly the tiles its cells need, a finite bound each.
void parse_levels(const nlohmann::json& j, const std::string& path, TileSetInfo& t) {
  const int T = 1 << t.grid.tile_log2;
  for (const auto& l : j.at("levels")) {
    const int L = int(t.tiles_x.size());
    const int nx = (t.tiles_cells_w(L) + T - 1) / T, ny = (t.tiles_cells_h(L) + T - 1) / T;
    const long long jx = whole(l.at("tiles").at(0), path, "tiles[0]", 0, kMaxTileSetSide);
    const long long jy = whole(l.at("tiles").at(1), path, "tiles[1]", 0, kMaxTileSetSide);
    if (jx != nx || jy != ny)
      throw InputError(fmt::format(
          "{}: level {} lists {} x {} tiles; its {} x {} cells need {} x {} tiles of {}", path, L,
          jx, jy, t.tiles_cells_w(L), t.tiles_cells_h(L), nx, ny, T));
    t.tiles_x.push_back(nx);
    t.tiles_y.push_back(ny);
    t.tile_max.push_back(l.at("tile_max_height").get<std::vector<float>>());
    if (t.tile_max.back().size() != std::size_t(nx) * std::size_t(ny))
      throw InputError(
          fmt::format("{}: tile_max_height of level {} has the wrong length", path, L));
    for (float m : t.tile_max.back())
      if (!(std::abs(m) <= kMaxAbsHeightM))
        throw InputError(fmt::format(
            "{}: tile_max_height of level {} holds {:g}, not a finite height within {:g} m", path,
            L, m, kMaxAbsHeightM));
  }
}

std::optional<FineLevelsInfo> parse_fine(const nlohmann::json& j, const std::string& path,
                                         const TerrainGrid& g) {
  if (!j.contains("fine")) return std::nullopt;
  const auto& fj = j["fine"];
  FineLevelsInfo fi;
  fi.levels = int(whole(fj.at("levels"), path, "fine.levels", 1, 12));
  fi.origin_x = int(whole(fj.at("origin").at(0), path, "fine.origin[0]", 0, 1 << 30));
  fi.origin_y = int(whole(fj.at("origin").at(1), path, "fine.origin[1]", 0, 1 << 30));
  for (const auto& bits : fj.at("present")) {
    const std::string b = bits.get<std::string>();
    auto& lv = fi.present.emplace_back(b.size());
    for (std::size_t i = 0; i < b.size(); ++i) lv[i] = b[i] == '1';
  }
  if (fi.levels < 1 || fi.levels > 12 || int(fi.present.size()) != fi.levels ||
      g.bound_levels + fi.levels > 31 || fi.origin_x < 0 || fi.origin_y < 0 ||
      (fi.origin_x | fi.origin_y) % ((1 << g.tile_log2) << (fi.levels - 1)) != 0)
    throw InputError(fmt::format("{}: inconsistent fine levels", path));
  return fi;
}

std::optional<GeoTransform> parse_geo(const nlohmann::json& j, const std::string& path) {
  if (!j.contains("geotransform")) return std::nullopt;
  GeoTransform gt;
  for (int k = 0; k < 6; ++k) {
    gt.gt[k] = j["geotransform"].at(std::size_t(k));
    if (!std::isfinite(gt.gt[k]))
      throw InputError(fmt::format("{}: geotransform[{}] is not a finite number", path, k));
  }
  gt.wkt = j.value("srs_wkt", "");
  return gt;
}

}  // namespace

TileSetInfo parse_tile_set_json(const std::string& text, const std::string& path) {
  TileSetInfo t;
  try {
    const nlohmann::json j = nlohmann::json::parse(text);
    if (!j.is_object() || !j.contains("format") || !j["format"].is_string() ||
        j["format"] != kFormat || !j.contains("version") || j["version"] != kVersion)
      throw InputError(fmt::format("{}: not a terrasprite tile set of version {}", path, kVersion));
    parse_grid(j, path, t.grid);
    parse_levels(j, path, t);
    t.fine = parse_fine(j, path, t.grid);
    t.geo = parse_geo(j, path);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("{}: malformed: {}", path, e.what()));
  }
  return t;
}

TileSetInfo read_tile_set(const std::string& dir) {
  detail::ensure_gdal();
  const std::string path = dir + "/tiles.json";
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(
        fmt::format("{}: cannot open (is {} a directory written by terrasprite tile?)", path, dir));
  TileSetInfo t = parse_tile_set_json(read_input_text(path, "tile set description"), path);
  t.dir = dir;
  const TerrainGrid& g = t.grid;
  check_raster(t.height_file(), g.width, g.height, g.coarsest_level, 1);
  check_raster(t.color_file(), g.width, g.height, g.coarsest_level, 3);
  check_raster(t.bound_file(), t.tiles_cells_w(0), t.tiles_cells_h(0), g.bound_levels - 1, 1);
  for (const std::string& p : {t.height_file(), t.color_file(), t.bound_file()})
    t.bytes_on_disk += (long long)std::filesystem::file_size(p, ec);
  if (t.fine) {
    auto fs = std::make_shared<TileSetInfo>(read_tile_set(dir + "/fine"));
    const FineLevelsInfo& fi = *t.fine;
    if (fs->fine || fs->grid.tile_log2 != g.tile_log2 || fs->grid.coarsest_level + 1 < fi.levels ||
        std::abs(fs->grid.spacing_x * (1 << fi.levels) - g.spacing_x) > 1e-6 * g.spacing_x ||
        std::abs(fs->grid.spacing_y * (1 << fi.levels) - g.spacing_y) > 1e-6 * g.spacing_y)
      throw InputError(fmt::format("{}/fine: does not fit the base's fine levels", dir));
    for (int l = 0; l < fi.levels; ++l)
      if (fi.present[std::size_t(l)].size() !=
          std::size_t(fs->tiles_x[std::size_t(l)]) * fs->tiles_y[std::size_t(l)])
        throw InputError(
            fmt::format("{}: present tiles of fine level {} have the wrong length", path, l));
    const int align = (1 << g.tile_log2) << (fi.levels - 1);
    const int fw = (g.width - 1) << fi.levels, fh = (g.height - 1) << fi.levels;
    if (((fs->grid.width - 1) % align != 0 && fi.origin_x + fs->grid.width - 1 != fw) ||
        ((fs->grid.height - 1) % align != 0 && fi.origin_y + fs->grid.height - 1 != fh) ||
        fi.origin_x + fs->grid.width - 1 > fw || fi.origin_y + fs->grid.height - 1 > fh)
      throw InputError(fmt::format("{}/fine: its window is not whole tiles of the fine grid", dir));
    fs->origin_x = fi.origin_x;
    fs->origin_y = fi.origin_y;
    fs->present = fi.present;
    t.bytes_on_disk += fs->bytes_on_disk;
    t.fine_set = std::move(fs);
  }
  return t;
}

}  // namespace terrasprite
