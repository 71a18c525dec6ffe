// SPDX-License-Identifier: MIT
// The voxel flythrough renderer (Cohen-Or, Rich, Lerner, Shenkar): columns
// along vertical planes through the eye are handed out to a pool of threads
// (TBB work stealing over a range of columns, no barrier inside a column),
// then the intermediate buffer is resampled to the image. The naive variant
// marches every pixel's ray on its own.
#include "terrasprite/voxel/voxel_renderer.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>
#include <thread>
#include <vector>

#include "terrasprite/common/error.h"
#include "voxel/column_march.h"
#include "voxel/column_rays.h"
#include "voxel/locate_row.h"
#include "voxel/resample_blend.h"
#include "voxel/vertical_planes.h"
#include "voxel/voxel_terrain_data.h"

namespace terrasprite {
namespace {

constexpr std::uint32_t kSkyPacked = std::uint32_t(kSkyColor[0]) |
                                     (std::uint32_t(kSkyColor[1]) << 8) |
                                     (std::uint32_t(kSkyColor[2]) << 16) | 0xff000000u;

int resolve_threads(int threads) {
  if (threads > 0) return threads;
  return std::max(1, int(std::thread::hardware_concurrency()));
}

// Camera-space ray through image point (x, y) in pixels, forward component 1.
struct ImageRays {
  glm::dvec3 f, r, u;
  double fx, fy, mx, my;
  ImageRays(const Camera& c, int w, int h) : f(c.forward()), r(c.right()), u(c.up()) {
    const double t = std::tan(c.fov_y_deg * 3.14159265358979323846 / 360.0);
    fx = w / (2.0 * t * c.aspect);
    fy = h / (2.0 * t);
    mx = w * 0.5;
    my = h * 0.5;
  }
  glm::dvec3 at(double x, double y) const { return f + ((x - mx) / fx) * r - ((y - my) / fy) * u; }
};

MarchSettings settings_for(const VoxelOptions& o, const Camera& cam, int height) {
  MarchSettings s;
  s.multires = o.variant == VoxelVariant::kMultires;
  s.blend = o.blend_levels;
  s.max_skip = o.max_skip && o.variant != VoxelVariant::kNaive;
  s.pixel_angle = cam.pixel_angle(height);
  s.ratio = o.pixel_voxel_ratio;
  return s;
}

}  // namespace

struct VoxelRenderer::State {
  const TerrainTiles& terrain;
  int w, h;
  VoxelOptions options;
  tbb::task_arena arena;
  // Intermediate buffer: per column its first sample index and offset.
  std::vector<std::int64_t> k0, k1;
  std::vector<std::size_t> offset;
  using Sample = PlaneSample;

  std::vector<Sample> samples;

  State(const TerrainTiles& t, int w_, int h_, const VoxelOptions& o)
      : terrain(t), w(w_), h(h_), options(o), arena(resolve_threads(o.threads)) {
    if (o.variant != VoxelVariant::kNaive) prefault_samples();
  }

  // The intermediate buffer sized and touched here, before any timed draw,
  // for the densest layout: about 1.27 samples a pixel per oversample^2 in
  // the slope layout and up to 1.83 in the tiered polar one looking straight
  // down (paper path, 2112 x 1188). Left to the first draw, faulting in and
  // growing those ~35 MB made it about twice as slow as the frames after it.
  // At most 256 MB here; a larger layout grows on its first draw.
  void prefault_samples() {
    const double est = 1.9 * double(w) * h * options.plane_oversample * options.plane_oversample;
    samples.resize(std::size_t(std::min(est, double(1 << 25))));
  }

  void naive(const Camera& cam, Frame& out);
  void planes(const Camera& cam, Frame& out);
};

VoxelRenderer::VoxelRenderer(const TerrainTiles& terrain, int width, int height,
                             VoxelOptions options) {
  if (width < 1 || height < 1 || width > 16384 || height > 16384)
    throw InputError(fmt::format("voxel renderer: image size {}x{} out of range", width, height));
  if (!(options.pixel_voxel_ratio > 0) || !std::isfinite(options.pixel_voxel_ratio))
    throw InputError(
        fmt::format("pixel_voxel_ratio {}: must be a positive number", options.pixel_voxel_ratio));
  if (!(options.plane_oversample >= 0.25 && options.plane_oversample <= 8))
    throw InputError(
        fmt::format("plane oversampling {}: must be within 0.25..8", options.plane_oversample));
  s_ = std::make_unique<State>(terrain, width, height, options);
}

VoxelRenderer::~VoxelRenderer() = default;

const VoxelOptions& VoxelRenderer::options() const {
  return s_->options;
}

std::string VoxelRenderer::name() const {
  return fmt::format("voxel-{}", to_string(s_->options.variant));
}

Frame VoxelRenderer::draw(const Camera& camera) {
  Frame out;
  draw_into(camera, out);
  return out;
}

void VoxelRenderer::draw_into(const Camera& camera, Frame& out) {
  out.prepare_for_overwrite(s_->w, s_->h);  // both passes write every pixel
  out.cls = FrameClass::kVoxel;
  out.camera = camera;
  const auto start = std::chrono::steady_clock::now();
  s_->arena.execute([&] {
    if (s_->options.variant == VoxelVariant::kNaive)
      s_->naive(camera, out);
    else
      s_->planes(camera, out);
  });
  out.ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

void VoxelRenderer::State::naive(const Camera& cam, Frame& out) {
  const double eye[3] = {cam.position.x, cam.position.y, cam.position.z};
  const ColumnMarcher marcher(terrain, eye, settings_for(options, cam, h));
  const ImageRays rays(cam, w, h);
  tbb::parallel_for(
      tbb::blocked_range<int>(0, h, 1),
      [&](const tbb::blocked_range<int>& range) {
        for (int y = range.begin(); y < range.end(); ++y)
          for (int x = 0; x < w; ++x) {
            const glm::dvec3 d = rays.at(x + 0.5, y + 0.5);
            const double hz = std::max(std::sqrt(d.x * d.x + d.y * d.y), 1e-12);
            const double slope = d.z / hz;
            MarchHit hit;
            marcher.march(hz > 1e-12 ? d.x / hz : 1.0, hz > 1e-12 ? d.y / hz : 0.0, {&slope, 1},
                          {&hit, 1});
            std::uint8_t* p = out.color.px(x, y);
            const std::uint32_t c = std::isfinite(hit.t) ? hit.color : kSkyPacked;
            p[0] = c & 0xff;
            p[1] = (c >> 8) & 0xff;
            p[2] = (c >> 16) & 0xff;
            p[3] = 255;
            out.depth[std::size_t(y) * w + x] =
                std::isfinite(hit.t) ? float(hit.t / hz) : Frame::kSky;
          }
      },
      tbb::simple_partitioner());
}

void VoxelRenderer::State::planes(const Camera& cam, Frame& out) {
  const PlaneLayout layout = make_plane_layout(cam, w, h, options.plane_oversample);
  const int n = layout.columns;
  k0.assign(n, 0);
  k1.assign(n, -1);
  offset.assign(std::size_t(n) + 1, 0);
  for (int c = 0; c < n; ++c) {
    std::int64_t a, b;
    if (layout.rows(c, w, h, a, b)) {
      k0[c] = std::max(a, layout.tier_start(c));
      k1[c] = b;
    }
    offset[c + 1] = offset[c] + std::size_t(std::max<std::int64_t>(0, k1[c] - k0[c] + 1));
  }
  // Grown with a quarter of headroom: left to the vector, the first frame
  // needing a few more samples than any before would double the buffer, and
  // touching that much fresh memory would make it slower than its neighbours.
  if (offset[n] > samples.capacity()) samples.reserve(offset[n] + offset[n] / 4);
  samples.resize(offset[n]);

  const double eye[3] = {cam.position.x, cam.position.y, cam.position.z};
  const ColumnMarcher marcher(terrain, eye, settings_for(options, cam, h));
  const ImageRays rays(cam, w, h);

  // One column: its rays bottom-up through the marcher, into the buffer.
  auto march_column = [&](int c) {
    thread_local std::vector<double> slopes, inv_hz;
    thread_local std::vector<MarchHit> hits;
    const std::int64_t count = k1[c] - k0[c] + 1;
    if (count <= 0) return;
    double wx, wy;
    layout.column_dir(c, wx, wy);
    slopes.resize(count);
    inv_hz.resize(count);
    hits.resize(count);
    // Samples in order of rising elevation; the ray is affine in k.
    const glm::dvec3 d0 = rays.at(layout.vx, layout.vy);
    const glm::dvec3 dk = rays.at(layout.vx + layout.dr * wx, layout.vy + layout.dr * wy) - d0;
    const double d0v[3] = {d0.x, d0.y, d0.z}, dkv[3] = {dk.x, dk.y, dk.z};
    column_rays(d0v, dkv, layout.rise_outward ? k0[c] : k1[c], layout.rise_outward ? 1 : -1, count,
                slopes.data(), inv_hz.data());
    for (std::int64_t i = 1; i < count; ++i) slopes[i] = std::max(slopes[i], slopes[i - 1]);
    // The plane's horizontal direction, from the sample farthest from V.
    const std::int64_t kf = k1[c];
    const glm::dvec3 df =
        rays.at(layout.vx + double(kf) * layout.dr * wx, layout.vy + double(kf) * layout.dr * wy);
    const double hf = std::sqrt(df.x * df.x + df.y * df.y);
    const double dx = hf > 1e-12 ? df.x / hf : 1.0, dy = hf > 1e-12 ? df.y / hf : 0.0;
    marcher.march(dx, dy, slopes, hits);
    for (std::int64_t i = 0; i < count; ++i) {
      const std::int64_t k = layout.rise_outward ? k0[c] + i : k1[c] - i;
      const std::size_t at = offset[c] + std::size_t(k - k0[c]);
      const bool hit = std::isfinite(hits[i].t);
      samples[at] = {hit ? hits[i].color : kSkyPacked,
                     hit ? float(hits[i].t * inv_hz[i]) : Frame::kSky};
    }
  };
  // Resampling, a row segment at a time: first each pixel's two columns (L
  // and L + s; s = 1 but in a tiered polar layout's inner tiers, where L is a
  // multiple of s, so cf / s, a product by 2^-log2(s), is exact) and sample rows kb, kb + 1, with a
  // prefetch of the samples; then the blends: bilinear colour, depth bilinear
  // on a surface and nearest across a silhouette. Splitting the two keeps many
  // pixels' buffer reads in flight at once (the blend waited on them).
  const double inv_dc = 1.0 / layout.dc, inv_dr = 1.0 / layout.dr;

  // Taps of pixels x0 .. x0 + count - 1 (count <= ResampleTaps::kMax) of row y.
  auto build_taps = [&](int x0, int count, const double* cf, const double* kf, ResampleTaps& t) {
    t.x0 = x0;
    t.count = count;
    for (int i = 0; i < count; ++i) {
      int s = 1;
      double cs = cf[i];
      if (layout.smax > 1) {
        s = layout.stride_at(kf[i]);
        cs *= std::bit_cast<double>(std::uint64_t(1023 - std::countr_zero(unsigned(s))) << 52);
      }
      const double cfl = double(floor_i64(cs)), kfl = double(floor_i64(kf[i]));
      const long cbase = long(cfl) * s;
      t.fc[i] = float(cs - cfl);
      t.fk[i] = float(kf[i] - kfl);
      unsigned ok = 0;
      const std::int64_t kb = std::int64_t(kfl);
      for (int a = 0; a < 2; ++a) {
        long c = cbase + a * s;
        t.at[a][i] = 0;
        if (c < 0 || c >= n) {
          if (!layout.wrap) continue;
          c = c < 0 ? c + n : c - n;
        }
        const std::int64_t c0k = k0[c], c1k = k1[c];
        const bool b0 = kb >= c0k && kb <= c1k, b1 = kb + 1 >= c0k && kb + 1 <= c1k;
        ok |= (unsigned(b0) | unsigned(b1) << 1) << (2 * a);
        t.at[a][i] = offset[c] + std::size_t(kb - c0k);
        if (b0 || b1) __builtin_prefetch(&samples[t.at[a][i] + (b0 ? 0 : 1)]);
      }
      t.ok[i] = ok;
    }
  };
  auto resample_span = [&](int y, int x0, int count, const double* cf, const double* kf) {
    thread_local ResampleTaps taps;
    std::uint8_t* row = out.color.px(0, y);
    float* depth = out.depth.data() + std::size_t(y) * w;
    for (int i = 0; i < count; i += ResampleTaps::kMax) {
      const int m = std::min(ResampleTaps::kMax, count - i);
      build_taps(x0 + i, m, cf + i, kf + i, taps);
      blend_taps(taps, samples.data(), samples.size(), kSkyPacked, row, depth);
    }
  };
  const SlopeRowLocator slope_row{layout.vx, layout.vy, layout.ex, layout.ey,
                                  layout.c0, inv_dc,    inv_dr};
  const PolarRowLocator polar_row{layout.vx, layout.vy, layout.ex, layout.ey,
                                  layout.c0, inv_dc,    inv_dr,    layout.wrap};
  thread_local std::vector<double> cfs, kfs;
  // Locates pixels x0 .. x0 + count - 1 of row y into cfs, kfs.
  auto locate_span = [&](int y, int x0, int count) {
    cfs.resize(std::size_t(count));
    kfs.resize(std::size_t(count));
    if (layout.polar) return locate_polar_row(polar_row, y, x0, count, cfs.data(), kfs.data());
    locate_slope_row(slope_row, y, x0, count, cfs.data(), kfs.data());
  };

  // March every column, then resample the image in vertical strips of 64
  // pixels (whole cache lines of the output rows), a row segment at a time.
  // Resampling each chunk of columns while it is in cache would write a few
  // pixels of every row per chunk and fetch the output lines several times;
  // the buffer reads are prefetched instead.
  tbb::parallel_for(
      tbb::blocked_range<int>(0, n, 2),
      [&](const tbb::blocked_range<int>& range) {
        for (int c = range.begin(); c < range.end(); ++c) march_column(c);
      },
      tbb::simple_partitioner());
  constexpr int kStrip = 64;
  tbb::parallel_for(tbb::blocked_range<int>(0, (w + kStrip - 1) / kStrip, 1),
                    [&](const tbb::blocked_range<int>& range) {
                      const int x0 = range.begin() * kStrip, x1 = std::min(w, range.end() * kStrip);
                      for (int y = 0; y < h; ++y) {
                        locate_span(y, x0, x1 - x0);
                        resample_span(y, x0, x1 - x0, cfs.data(), kfs.data());
                      }
                    });
}

}  // namespace terrasprite
