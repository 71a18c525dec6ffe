// SPDX-License-Identifier: MIT
// terrasprite tile: a terrain to Cloud-Optimized GeoTIFFs of the ray caster's
// own pyramid (load -> pyramid -> COGs + tiles.json), for streaming.
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <memory>

#include "cli_common.h"
#include "commands.h"
#include "terrasprite/common/error.h"
#include "terrasprite/stream/fine_insets.h"
#include "terrasprite/stream/insets.h"
#include "terrasprite/output/output_dir.h"
#include "terrasprite/stream/tiled_terrain.h"
#include "terrasprite/voxel/voxel_renderer.h"

namespace terrasprite::cli {

namespace {

// Composites the --inset rasters into `hf` (see terrasprite/stream/insets.h) and
// returns the grid's georeferencing (kept through --resample: the grid's
// corner samples are the source's corner pixel centres).
std::optional<GeoTransform> add_insets(Heightfield& hf, const std::string& dem,
                                       const std::vector<InsetSpec>& specs,
                                       std::vector<InsetResult>& results, GridGeo& g) {
  const auto [sw, sh] =
      hf.resampled_to && !dem.empty() ? raster_size(dem) : std::pair{hf.width, hf.height};
  g = grid_geo(hf, sw, sh);
  results = composite_insets(hf, g, specs);
  for (const InsetResult& r : results)
    fmt::print("{}: {} samples from the inset ({} at full weight)\n", r.path, r.samples_replaced,
               r.samples_full);
  GeoTransform geo;
  const double gt[6] = {g.x0 - 0.5 * g.dx, g.dx, 0, g.y0 + 0.5 * g.dy, 0, -g.dy};
  std::copy(gt, gt + 6, geo.gt);
  geo.wkt = g.wkt;
  return geo;
}

// Bytes the in-memory writer holds per level-0 sample: the terrain, its
// colour and the pyramid (heights, colours, bounds; a third more for the
// coarser levels), measured about 24 at 16385^2.
constexpr double kInMemoryBytesPerSample = 24.0;

double physical_memory_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page > 0 ? double(pages) * double(page) : 0.0;
}

void print_summary(const std::string& dir, int lg, std::chrono::steady_clock::time_point t0) {
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const TileSetInfo info = read_tile_set(dir);
  fmt::print("{}: {} x {} samples, {} levels, {}-cell tiles, {:.1f} MB on disk, {:.1f} s\n", dir,
             info.grid.width, info.grid.height, info.grid.coarsest_level + 1, 1 << lg,
             info.bytes_on_disk / 1e6, s);
  if (info.fine_set) {
    const auto& p0 = info.fine->present[0];
    fmt::print(
        "{}/fine: {} fine levels ({:.4g} m), {} x {} samples, {} of {} finest tiles with "
        "inset data\n",
        dir, info.fine->levels, info.fine_set->grid.spacing_x, info.fine_set->grid.width,
        info.fine_set->grid.height, std::count(p0.begin(), p0.end(), 1), p0.size());
  }
}

// --strips auto: strip-wise unless insets need the grid in memory, when the
// in-memory writer would need more than half the machine's memory or the
// grid is past what load_terrain holds (--resample above 16385).
bool use_strips(const std::string& mode, const TerrainOptions& t, bool insets) {
  if (mode == "never") return false;
  if (insets) {
    if (mode == "always")
      throw InputError("--strips always: insets (--inset) need the terrain in memory");
    return false;
  }
  if (mode == "always") return true;
  std::pair<int, int> size{t.synthetic_size, t.synthetic_size};
  if (t.resample) {
    size = {t.resample, t.resample};
  } else if (!t.dem.empty()) {
    try {
      size = raster_size(t.dem);
    } catch (const InputError&) {
      return false;  // the loader names what is wrong with the file
    }
  }
  const auto [w, h] = size;
  const double need = kInMemoryBytesPerSample * double(w) * double(h);
  return t.resample > 16385 || need > 0.5 * physical_memory_bytes();
}

// The strip-wise path: the terrain never held at its final size.
void tile_by_strips(const TerrainOptions& to, const TileWriteOptions& wo, const std::string& dir,
                    const OutputPolicy& policy) {
  std::vector<std::string> warnings;
  const LargeTerrain t = load_large_terrain(to, &warnings);
  for (const auto& w : warnings) fmt::print(stderr, "warning: {}\n", w);
  std::optional<GeoTransform> geo = t.source.geo;
  if (t.resampled) geo.reset();  // the source's transform no longer fits the grid
  OutputDir out(dir, policy);
  const StripWriteStats s =
      write_tiled_terrain_strips(terrain_rows(t), geo, out.partial().string(), wo);
  out.commit();
  fmt::print(
      "strip-wise: {}-row bands, pyramid {:.1f} s ({:.1f} GB of temporary files), COGs {:.1f} s\n",
      s.band_rows, s.pyramid_s, s.temp_bytes / 1e9, s.cogs_s);
}

}  // namespace

void add_tile(CLI::App& app, const OutputPolicy& policy) {
  auto* cmd = app.add_subcommand(
      "tile", "write a terrain as Cloud-Optimized GeoTIFFs of its pyramid (for bench stream)");
  struct Opts {
    TerrainOptions terrain;
    TileWriteOptions write;
    int tile_size = 128;
    std::string out;
    std::vector<std::string> insets;
    int fine_levels = 0;
    std::string strips = "auto";
  };
  auto o = std::make_shared<Opts>();
  add_terrain_options(*cmd, o->terrain);
  cmd->add_option("--out", o->out,
                  "output directory (height.tif, color.tif, bound.tif, tiles.json)")
      ->required();
  cmd->add_option("--tile-size", o->tile_size,
                  "tile edge in cells: 16, 32, ..., 512 (default 128)");
  cmd->add_option("--color-compress", o->write.color_compress, "JPEG (default), WEBP or DEFLATE")
      ->transform(CLI::IsMember({"JPEG", "WEBP", "DEFLATE"}, CLI::ignore_case));
  cmd->add_option("--color-quality", o->write.color_quality,
                  "JPEG/WEBP quality 1..100 (default 90)");
  cmd->add_option("--inset", o->insets,
                  "FILE[:blend=N]: a finer raster (any CRS GDAL reprojects) whose samples replace "
                  "the terrain's where it has data, faded in over N grid samples (default 4); "
                  "repeatable, later over earlier; needs --dem with a CRS")
      ->take_all();
  cmd->add_option("--fine-levels", o->fine_levels,
                  "K: also keep the insets at their own resolution, as sparse levels 2^K times "
                  "finer than the terrain's (1..8; 0, the default: composited only), streamed "
                  "with it");
  cmd->add_option("--height-compress", o->write.height_compress, "DEFLATE (default) or ZSTD")
      ->transform(CLI::IsMember({"DEFLATE", "ZSTD"}, CLI::ignore_case));
  cmd->add_option("--strips", o->strips,
                  "auto (default), always or never: build the pyramid in strips of rows, "
                  "never holding the terrain (auto: without --inset, when the in-memory writer "
                  "would need over half the memory or --resample is above 16385; up to 65537)")
      ->transform(CLI::IsMember({"auto", "always", "never"}, CLI::ignore_case));
  cmd->callback([o, &policy] {
    int lg = 0;
    while ((1 << lg) < o->tile_size) ++lg;
    if ((1 << lg) != o->tile_size || lg < 4 || lg > 9)
      throw InputError(fmt::format("--tile-size {}: must be 16, 32, ..., 512", o->tile_size));
    o->write.tile_log2 = lg;
    if (o->fine_levels != 0 && (o->insets.empty() || o->fine_levels < 1 || o->fine_levels > 8))
      throw InputError(fmt::format("--fine-levels {}: must be 1..8, with --inset", o->fine_levels));
    std::vector<InsetSpec> specs;
    for (const std::string& a : o->insets) specs.push_back(parse_inset(a));
    check_outputs(policy, o->out, {});
    const auto t0 = std::chrono::steady_clock::now();
    if (use_strips(o->strips, o->terrain, !specs.empty())) {
      tile_by_strips(o->terrain, o->write, o->out, policy);
      print_summary(o->out, lg, t0);
      return;
    }
    std::unique_ptr<VoxelTerrain> vt;
    std::optional<GeoTransform> geo;
    std::unique_ptr<OutputDir> out;
    {  // the terrain is freed once the pyramid holds what the files need
      Terrain t = load_terrain_verbose(o->terrain);
      geo = t.heights.geo;
      if (t.heights.resampled_to) geo.reset();  // the source's transform no longer fits the grid
      GridGeo g;
      if (!specs.empty()) geo = add_insets(t.heights, o->terrain.dem, specs, o->write.insets, g);
      out = std::make_unique<OutputDir>(o->out, policy);
      if (o->fine_levels > 0)  // DIR/fine first: the base's bounds must cover it
        o->write.fine =
            write_fine_insets(t, g, specs, o->fine_levels, o->write, out->partial().string());
      vt = std::make_unique<VoxelTerrain>(t);
    }
    OutputDir& out_dir = *out;
    write_tiled_terrain(*vt, geo, out_dir.partial().string(), o->write);
    o->write.fine.reset();  // the cell maxima are written; free them
    out_dir.commit();
    print_summary(o->out, lg, t0);
  });
}

}  // namespace terrasprite::cli
