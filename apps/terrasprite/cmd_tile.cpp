// SPDX-License-Identifier: MIT
// terrasprite tile: a terrain to Cloud-Optimized GeoTIFFs of the ray caster's
// own pyramid (load -> pyramid -> COGs + tiles.json), for streaming.
#include <fmt/format.h>

#include <chrono>
#include <memory>

#include "cli_common.h"
#include "commands.h"
#include "terrasprite/error.h"
#include "terrasprite/insets.h"
#include "terrasprite/output_dir.h"
#include "terrasprite/tiled_terrain.h"
#include "terrasprite/voxel_renderer.h"

namespace terrasprite::cli {

namespace {

// Composites the --inset rasters into `hf` (see terrasprite/insets.h) and
// returns the grid's georeferencing (kept through --resample: the grid's
// corner samples are the source's corner pixel centres).
std::optional<GeoTransform> add_insets(Heightfield& hf, const std::string& dem,
                                       const std::vector<std::string>& args,
                                       std::vector<InsetResult>& results) {
  std::vector<InsetSpec> specs;
  for (const std::string& a : args) specs.push_back(parse_inset(a));
  const auto [sw, sh] =
      hf.resampled_to && !dem.empty() ? raster_size(dem) : std::pair{hf.width, hf.height};
  const GridGeo g = grid_geo(hf, sw, sh);
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

}  // namespace

void add_tile(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "tile", "write a terrain as Cloud-Optimized GeoTIFFs of its pyramid (for bench stream)");
  struct Opts {
    TerrainOptions terrain;
    TileWriteOptions write;
    int tile_size = 128;
    std::string out;
    std::vector<std::string> insets;
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
  cmd->add_option("--height-compress", o->write.height_compress, "DEFLATE (default) or ZSTD")
      ->transform(CLI::IsMember({"DEFLATE", "ZSTD"}, CLI::ignore_case));
  cmd->callback([o] {
    int lg = 0;
    while ((1 << lg) < o->tile_size) ++lg;
    if ((1 << lg) != o->tile_size || lg < 4 || lg > 9)
      throw InputError(fmt::format("--tile-size {}: must be 16, 32, ..., 512", o->tile_size));
    o->write.tile_log2 = lg;
    check_outputs(o->out, {});
    const auto t0 = std::chrono::steady_clock::now();
    std::unique_ptr<VoxelTerrain> vt;
    std::optional<GeoTransform> geo;
    {  // the terrain is freed once the pyramid holds what the files need
      Terrain t = load_terrain_verbose(o->terrain);
      geo = t.heights.geo;
      if (t.heights.resampled_to) geo.reset();  // the source's transform no longer fits the grid
      if (!o->insets.empty())
        geo = add_insets(t.heights, o->terrain.dem, o->insets, o->write.insets);
      vt = std::make_unique<VoxelTerrain>(t);
    }
    OutputDir out(o->out, output_policy());
    write_tiled_terrain(*vt, geo, out.partial().string(), o->write);
    out.commit();
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const TileSetInfo info = read_tile_set(o->out);
    fmt::print("{}: {} x {} samples, {} levels, {}-cell tiles, {:.1f} MB on disk, {:.1f} s\n",
               o->out, info.grid.width, info.grid.height, info.grid.coarsest_level + 1, 1 << lg,
               info.bytes_on_disk / 1e6, s);
  });
}

}  // namespace terrasprite::cli
