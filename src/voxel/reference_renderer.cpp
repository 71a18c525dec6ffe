// SPDX-License-Identifier: MIT
// Quality ground truth for the voxel renderer: per-pixel ray marching with
// small steps against the exact bilinear height surface, crossings refined
// by bisection, full-resolution colour, n x n supersampling. Empty space is
// skipped with the max pyramid, which bounds the surface and so leaves the
// result unchanged.
#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <thread>

#include "terrasprite/common/error.h"
#include "voxel/voxel_terrain_data.h"

namespace terrasprite {

struct VoxelReference::State {
  const VoxelTerrain& terrain;
  int w, h;
  ReferenceOptions options;
  tbb::task_arena arena;
  State(const VoxelTerrain& t, int w_, int h_, const ReferenceOptions& o)
      : terrain(t),
        w(w_),
        h(h_),
        options(o),
        arena(o.threads > 0 ? o.threads : std::max(1, int(std::thread::hardware_concurrency()))) {}
};

VoxelReference::VoxelReference(const VoxelTerrain& terrain, int width, int height,
                               ReferenceOptions options) {
  if (width < 1 || height < 1 || width > 16384 || height > 16384)
    throw InputError(
        fmt::format("reference renderer: image size {}x{} out of range", width, height));
  if (options.supersample < 1 || options.supersample > 8)
    throw InputError(fmt::format("reference supersampling {}: must be 1..8", options.supersample));
  if (!(options.step_cells > 0 && options.step_cells <= 1))
    throw InputError(
        fmt::format("reference step {}: must be within (0, 1] cells", options.step_cells));
  s_ = std::make_unique<State>(terrain, width, height, options);
}

VoxelReference::~VoxelReference() = default;

std::string VoxelReference::name() const {
  return fmt::format("voxel-reference-{}x{}", s_->options.supersample, s_->options.supersample);
}

namespace {

// One ray: horizontal distance to the first crossing (+inf if none) and colour.
struct RefRay {
  const VoxelTerrain::Data& d;
  double eu, ev, ez, step_m;

  bool cast(double dx, double dy, double slope, double& t_hit, float rgb[3]) const {
    if (!d.has_area()) return false;
    const PyramidLevel& lev = d.levels[0];
    const double gu = dx / d.sx, gv = -dy / d.sy;
    double t0 = 0, t1 = std::numeric_limits<double>::infinity();
    auto clip = [&](double e, double g, double hi) {
      if (std::abs(g) < 1e-300) return e >= 0 && e <= hi;
      double a = -e / g, b = (hi - e) / g;
      t0 = std::max(t0, std::min(a, b));
      t1 = std::min(t1, std::max(a, b));
      return true;
    };
    if (!clip(eu, gu, d.w - 1) || !clip(ev, gv, d.h - 1) || !(t1 >= t0)) return false;
    auto gap = [&](double t) {
      return ez + slope * t - bilinear_height(lev, eu + t * gu, ev + t * gv);
    };
    const double gmax = std::max({std::abs(gu), std::abs(gv), 1e-300});
    const int kmax = int(d.maxes.size()) - 1;
    double t = t0, g = gap(t);
    if (g <= 0) {
      if (t0 > 0) return false;  // enters the grid's side under its edge: passes below the surface
      t_hit = t;                 // the eye is under the surface
    } else {
      bool found = false;
      while (t < t1) {
        // Skip while the ray stays above the dilated max of the cell around it.
        bool skipped = false;
        for (int k = kmax; k >= 1; --k) {
          const double reach = double(1 << k) / gmax;
          const double te = std::min(t + reach, t1);
          const double zmin = ez + slope * (slope < 0 ? te : t);
          const MaxLevel& ml = d.maxes[k];
          const int a = std::clamp(int((eu + t * gu) / double(1 << k)), 0, ml.w - 1);
          const int b = std::clamp(int((ev + t * gv) / double(1 << k)), 0, ml.h - 1);
          if (zmin > ml.at(a, b)) {
            t = te;
            skipped = true;
            break;
          }
        }
        if (skipped) {
          if (t >= t1) break;
          g = gap(t);
          continue;
        }
        const double tn = std::min(t + step_m, t1);
        const double gn = gap(tn);
        if (gn <= 0) {
          double lo = t, hi = tn;  // gap(lo) > 0 >= gap(hi)
          for (int i = 0; i < 24; ++i) {
            double mid = 0.5 * (lo + hi);
            (gap(mid) > 0 ? lo : hi) = mid;
          }
          t_hit = hi;
          found = true;
          break;
        }
        if (tn >= t1) break;
        t = tn;
        g = gn;
      }
      if (!found) return false;
    }
    bilinear_color(lev, eu + t_hit * gu, ev + t_hit * gv, rgb);
    return true;
  }
};

}  // namespace

Frame VoxelReference::draw(const Camera& cam) {
  State& s = *s_;
  Frame out;
  out.color = Image(s.w, s.h);
  out.depth.assign(static_cast<std::size_t>(s.w) * s.h, Frame::kSky);
  out.cls = FrameClass::kReference;
  out.camera = cam;
  const auto start = std::chrono::steady_clock::now();
  const VoxelTerrain::Data& d = s.terrain.data();
  const RefRay ray{d, d.grid_u(cam.position.x), d.grid_v(cam.position.y), cam.position.z,
                   s.options.step_cells * std::min(d.sx, d.sy)};
  const int n = s.options.supersample;
  const double tn = std::tan(cam.fov_y_deg * 3.14159265358979323846 / 360.0);
  const glm::dvec3 f = cam.forward(), r = cam.right(), u = cam.up();
  s.arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<int>(0, s.h, 1),
                      [&](const tbb::blocked_range<int>& range) {
                        for (int y = range.begin(); y < range.end(); ++y)
                          for (int x = 0; x < s.w; ++x) {
                            float acc[3] = {0, 0, 0};
                            double dsum = 0;
                            int hits = 0;
                            for (int b = 0; b < n; ++b)
                              for (int a = 0; a < n; ++a) {
                                const double px = x + (a + 0.5) / n, py = y + (b + 0.5) / n;
                                const double cx = (2.0 * px / s.w - 1.0) * tn * cam.aspect,
                                             cy = (1.0 - 2.0 * py / s.h) * tn;
                                const glm::dvec3 dir = f + cx * r + cy * u;  // forward component 1
                                const double hz = std::max(std::hypot(dir.x, dir.y), 1e-12);
                                const double dx = hz > 1e-12 ? dir.x / hz : 1.0,
                                             dy = hz > 1e-12 ? dir.y / hz : 0.0;
                                double t;
                                float rgb[3];
                                if (ray.cast(dx, dy, dir.z / hz, t, rgb)) {
                                  for (int c = 0; c < 3; ++c) acc[c] += rgb[c];
                                  dsum += t / hz;
                                  ++hits;
                                } else {
                                  for (int c = 0; c < 3; ++c) acc[c] += kSkyColor[c];
                                }
                              }
                            std::uint8_t* p = out.color.px(x, y);
                            for (int c = 0; c < 3; ++c)
                              p[c] = std::uint8_t(std::clamp(acc[c] / (n * n) + 0.5f, 0.f, 255.f));
                            p[3] = 255;
                            if (hits) out.depth[std::size_t(y) * s.w + x] = float(dsum / hits);
                          }
                      });
  });
  out.ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace terrasprite
