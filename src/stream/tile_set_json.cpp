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
  if (!f) throw InputError(fmt::format("{}: cannot write", path));
}

TileSetInfo read_tile_set(const std::string& dir) {
  detail::ensure_gdal();
  const std::string path = dir + "/tiles.json";
  std::ifstream f(path);
  if (!f)
    throw InputError(
        fmt::format("{}: cannot open (is {} a directory written by terrasprite tile?)", path, dir));
  TileSetInfo t;
  t.dir = dir;
  try {
    const nlohmann::json j = nlohmann::json::parse(f);
    if (j.at("format") != kFormat || j.at("version") != kVersion)
      throw InputError(fmt::format("{}: not a terrasprite tile set of version {}", path, kVersion));
    TerrainGrid& g = t.grid;
    g.width = j.at("samples")[0];
    g.height = j.at("samples")[1];
    g.spacing_x = j.at("spacing_m")[0];
    g.spacing_y = j.at("spacing_m")[1];
    g.min_height = j.at("height_min");
    g.max_height = j.at("height_max");
    g.finest_level = 0;
    g.coarsest_level = j.at("coarsest_level");
    g.bound_levels = j.at("bound_levels");
    const int T = j.at("tile_cells");
    g.tile_log2 = 0;
    while ((1 << g.tile_log2) < T) ++g.tile_log2;
    if (g.width < 2 || g.height < 2 || (1 << g.tile_log2) != T || g.bound_levels < 1 ||
        g.bound_levels > 31 || g.coarsest_level < 0 || g.coarsest_level >= g.bound_levels ||
        int(j.at("levels").size()) != g.bound_levels)
      throw InputError(fmt::format("{}: inconsistent grid or levels", path));
    for (const auto& l : j.at("levels")) {
      t.tiles_x.push_back(l.at("tiles")[0]);
      t.tiles_y.push_back(l.at("tiles")[1]);
      t.tile_max.push_back(l.at("tile_max_height").get<std::vector<float>>());
      if (t.tile_max.back().size() != std::size_t(t.tiles_x.back()) * t.tiles_y.back())
        throw InputError(fmt::format("{}: tile_max_height of level {} has the wrong length", path,
                                     int(t.tile_max.size()) - 1));
    }
    if (j.contains("fine")) {
      const auto& fj = j["fine"];
      FineLevelsInfo fi;
      fi.levels = fj.at("levels");
      fi.origin_x = fj.at("origin")[0];
      fi.origin_y = fj.at("origin")[1];
      for (const auto& bits : fj.at("present")) {
        const std::string b = bits.get<std::string>();
        auto& lv = fi.present.emplace_back(b.size());
        for (std::size_t i = 0; i < b.size(); ++i) lv[i] = b[i] == '1';
      }
      if (fi.levels < 1 || fi.levels > 12 || int(fi.present.size()) != fi.levels ||
          g.bound_levels + fi.levels > 31 ||
          (fi.origin_x | fi.origin_y) % ((1 << g.tile_log2) << (fi.levels - 1)) != 0)
        throw InputError(fmt::format("{}: inconsistent fine levels", path));
      t.fine = std::move(fi);
    }
    if (j.contains("geotransform")) {
      GeoTransform gt;
      for (int k = 0; k < 6; ++k) gt.gt[k] = j["geotransform"][k];
      gt.wkt = j.value("srs_wkt", "");
      t.geo = gt;
    }
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("{}: malformed: {}", path, e.what()));
  }
  const TerrainGrid& g = t.grid;
  check_raster(t.height_file(), g.width, g.height, g.coarsest_level, 1);
  check_raster(t.color_file(), g.width, g.height, g.coarsest_level, 3);
  check_raster(t.bound_file(), t.tiles_cells_w(0), t.tiles_cells_h(0), g.bound_levels - 1, 1);
  std::error_code ec;
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
