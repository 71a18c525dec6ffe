// SPDX-License-Identifier: MIT
// LDR-FLIP: P. Andersson, J. Nilsson, T. Akenine-Moller, M. Oskarsson,
// K. Astrom, M. D. Fairchild, "FLIP: A Difference Evaluator for Alternating
// Images", Proc. ACM Comput. Graph. Interact. Tech. 3(2), 2020 (HPG 2020).
// Colour pipeline: sRGB -> linear RGB -> YyCxCz; contrast-sensitivity filters
// per opponent channel; clamp in linear RGB; CIELAB with the Hunt adjustment;
// HyAB distance ^ qc (0.7), remapped with pc = 0.4, pt = 0.95 against the
// green-blue distance. Feature pipeline: edge (1st derivative of Gaussian) and
// point (2nd derivative) detectors on luminance, sd = 0.5 * 0.082 * ppd,
// max of the feature-magnitude differences, (./sqrt 2) ^ qf (0.5).
// Per pixel: E = Ec ^ (1 - Ef).
//
// All filters are separable (the blue-yellow CSF is a sum of two separable
// Gaussians). Rows are streamed per band as in ssim_wang.cpp: a ring of
// horizontally filtered rows, vertical filters and the per-pixel formula run
// row by row while the ring is in cache. Borders replicate the edge pixel, as
// NVIDIA's reference code does (the paper leaves borders open).
#include <fmt/format.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "quality/filter.h"
#include "quality/flip_color.h"
#include "quality/median.h"
#include "quality/planes.h"
#include "quality/row_sum.h"
#include "terrasprite/common/error.h"

namespace terrasprite::quality {

namespace {

using detail::Kernel;

// One Gaussian term exp(-pi^2 x^2 / b), x in degrees, sampled on |i| <= radius
// pixels: the 1D factor of a CSF filter term, normalised to sum 1. `sum` gets
// the untrimmed sum (the 2D normalisation needs it). Tails below 1e-9 of the
// peak are dropped: far below float resolution, and A/RG then need 13-15 taps
// instead of the reference radius's 21.
Kernel csf_term(double b, double ppd, int radius, double& sum) {
  std::vector<double> g(2 * radius + 1);
  sum = 0;
  for (int i = -radius; i <= radius; ++i) {
    const double x = i / ppd;
    sum += g[i + radius] = std::exp(-std::numbers::pi * std::numbers::pi * x * x / b);
  }
  int r = radius;
  while (r > 0 && g[radius + r] < 1e-9) --r;
  Kernel k;
  k.radius = r;
  k.w.resize(k.taps());
  for (int i = 0; i < k.taps(); ++i) k.w[i] = static_cast<float>(g[radius - r + i] / sum);
  k.find_symmetry();
  return k;
}

// A feature detector's 1D derivative factor, positive taps scaled to sum 1 and
// negative taps to sum -1 (with the Gaussian factor normalised to 1 this is the
// 2D normalisation of the paper's filters).
Kernel signed_normalised(const std::vector<double>& h) {
  double pos = 0, neg = 0;
  for (double v : h) (v > 0 ? pos : neg) += v;
  Kernel k;
  k.radius = static_cast<int>(h.size() / 2);
  k.w.resize(h.size());
  for (std::size_t i = 0; i < h.size(); ++i)
    k.w[i] =
        static_cast<float>(h[i] > 0 ? (pos > 0 ? h[i] / pos : 0) : (neg < 0 ? -h[i] / neg : 0));
  k.find_symmetry();
  return k;
}

struct Filters {
  Kernel a, rg, by1, by2;  // CSF: achromatic, red-green, blue-yellow (two terms)
  float by_w1 = 1, by_w2 = 0;
  Kernel gauss, edge, point;  // feature detectors: x-derivative factor times Gaussian in y
  int radius = 0;

  explicit Filters(double ppd) {
    // CSF parameters (a1, b1, a2, b2) of the paper; b in degrees^2.
    constexpr double b_a = 0.0047, b_rg = 0.0053, a1_by = 34.1, b1_by = 0.04, a2_by = 13.5,
                     b2_by = 0.025;
    // One radius for all channels, from the widest term: 3 standard deviations.
    const int r = static_cast<int>(
        std::ceil(3 * std::sqrt(b1_by / (2 * std::numbers::pi * std::numbers::pi)) * ppd));
    double s_a, s_rg, s1, s2;
    a = csf_term(b_a, ppd, r, s_a);
    rg = csf_term(b_rg, ppd, r, s_rg);
    by1 = csf_term(b1_by, ppd, r, s1);
    by2 = csf_term(b2_by, ppd, r, s2);
    // The 2D blue-yellow filter is a1 sqrt(pi/b1) G1(x)G1(y) + a2 sqrt(pi/b2)
    // G2(x)G2(y), normalised to sum 1: a mix of the two normalised separable terms.
    const double t1 = a1_by * std::sqrt(std::numbers::pi / b1_by) * s1 * s1;
    const double t2 = a2_by * std::sqrt(std::numbers::pi / b2_by) * s2 * s2;
    by_w1 = static_cast<float>(t1 / (t1 + t2));
    by_w2 = static_cast<float>(t2 / (t1 + t2));

    const double sd = 0.5 * 0.082 * ppd;  // w = 0.082 degrees peak to trough
    const int fr = static_cast<int>(std::ceil(3 * sd));
    std::vector<double> g(2 * fr + 1), he(g.size()), hp(g.size());
    double gsum = 0;
    for (int i = -fr; i <= fr; ++i) {
      const double v = std::exp(-(i * i) / (2 * sd * sd));
      g[i + fr] = v, gsum += v;
      he[i + fr] = -i * v;
      hp[i + fr] = (i * i / (sd * sd) - 1) * v;
    }
    gauss.radius = fr;
    gauss.w.resize(g.size());
    for (std::size_t i = 0; i < g.size(); ++i) gauss.w[i] = static_cast<float>(g[i] / gsum);
    gauss.find_symmetry();
    edge = signed_normalised(he);
    point = signed_normalised(hp);
    radius = std::max({a.radius, rg.radius, by1.radius, by2.radius, fr});
  }
};

// Horizontal planes per image, in ring order.
enum HPlane { kA, kRG, kBY1, kBY2, kFG, kFE, kFP, kHPlanes };

}  // namespace

FlipResult flip(const ImageView& reference, const ImageView& test, const FlipOptions& options,
                Mask mask) {
  detail::check_inputs("flip", reference, test, mask);
  if (!std::isfinite(options.ppd) || options.ppd <= 0 || options.ppd > 1000)
    throw InputError(
        fmt::format("flip: pixels per degree must be in (0, 1000], got {}", options.ppd));
  const int w = reference.width, h = reference.height;
  const Filters f(options.ppd);
  const detail::FlipColor& color = detail::flip_color();
  const int R = f.radius, K = 2 * R + 1;
  const ImageView* images[2] = {&reference, &test};

  FlipResult result;
  std::vector<float> map(static_cast<std::size_t>(w) * h);

  // Work items are tiles: bands of rows (a few per thread, tall enough that
  // the 2R extra rows filtered at a band's edges stay a small overhead) times
  // columns of at most kTile pixels, so a tile's ring of 14 planes x (2R + 1)
  // rows stays in L2 (a full 1080p row width would need 2.3 MB).
  constexpr int kTile = 512;
  const int threads = tbb::this_task_arena::max_concurrency();
  const int band = std::max(32, (h + 2 * threads - 1) / (2 * threads));
  const int bands = (h + band - 1) / band;
  const int tile_w = std::min(w, kTile);
  const int tiles = (w + tile_w - 1) / tile_w;
  std::vector<double> tile_sums(static_cast<std::size_t>(h) * tiles, 0.0);

  tbb::parallel_for(0, bands * tiles, [&](int item) {
    const int y0 = item / tiles * band, y1 = std::min(h, y0 + band);
    const int ti = item % tiles, x0 = ti * tile_w, x1 = std::min(w, x0 + tile_w);
    const int tw = x1 - x0;
    const std::size_t T = static_cast<std::size_t>(tw);
    std::vector<float> ring(2 * kHPlanes * K * T);
    auto slot = [&](int img, int plane, int v) {  // v: virtual row, y0 - R <= v < y1 + R
      return ring.data() +
             ((static_cast<std::size_t>(img) * kHPlanes + plane) * K + (v - y0 + R) % K) * T;
    };
    // Padded input row: columns x0 - R .. x1 + R, clamped to the image.
    const std::size_t P = T + 2 * R;
    const int lo = std::max(0, x0 - R), hi = std::min(w, x1 + R);
    const int lead = lo - (x0 - R), valid = hi - lo;
    std::vector<float> in(4 * P);  // Yy, Cx, Cz, luminance
    std::vector<float> vert(2 * 8 * T);
    std::vector<const float*> ptr(K);

    auto vfilter = [&](int img, int plane, const Kernel& k, int y, float* out) {
      for (int i = 0; i < k.taps(); ++i) ptr[i] = slot(img, plane, y - k.radius + i);
      detail::filter_column(ptr.data(), k.taps(), k.w.data(), tw, out, k.symmetry);
    };
    auto hfilter = [&](const float* padded, const Kernel& k, float* out) {
      detail::filter_row(padded + (R - k.radius), tw, k.w.data(), k.taps(), out, k.symmetry);
    };

    for (int v = y0 - R; v < y1 + R; ++v) {
      const int sy = std::clamp(v, 0, h - 1);
      for (int img = 0; img < 2; ++img) {
        const ImageView& im = *images[img];
        color.to_ycxcz_row(im.row(sy) + static_cast<std::size_t>(lo) * im.channels, im.channels,
                           valid, in.data() + lead, in.data() + P + lead, in.data() + 2 * P + lead,
                           in.data() + 3 * P + lead);
        for (int c = 0; c < 4; ++c) {  // replicate the image's edge pixels
          float* row = in.data() + c * P;
          std::fill(row, row + lead, row[lead]);
          std::fill(row + lead + valid, row + P, row[lead + valid - 1]);
        }
        hfilter(in.data(), f.a, slot(img, kA, v));
        hfilter(in.data() + P, f.rg, slot(img, kRG, v));
        hfilter(in.data() + 2 * P, f.by1, slot(img, kBY1, v));
        hfilter(in.data() + 2 * P, f.by2, slot(img, kBY2, v));
        hfilter(in.data() + 3 * P, f.gauss, slot(img, kFG, v));
        hfilter(in.data() + 3 * P, f.edge, slot(img, kFE, v));
        hfilter(in.data() + 3 * P, f.point, slot(img, kFP, v));
      }
      const int y = v - R;  // rows y - R .. y + R are in the ring now
      if (y < y0) continue;
      detail::FlipRows rows[2];
      for (int img = 0; img < 2; ++img) {
        float* o = vert.data() + img * 8 * T;
        vfilter(img, kA, f.a, y, o);
        vfilter(img, kRG, f.rg, y, o + T);
        vfilter(img, kBY1, f.by1, y, o + 2 * T);
        vfilter(img, kBY2, f.by2, y, o + 3 * T);
        vfilter(img, kFE, f.gauss, y, o + 4 * T);  // edge x: d/dx then Gaussian in y
        vfilter(img, kFG, f.edge, y, o + 5 * T);   // edge y
        vfilter(img, kFP, f.gauss, y, o + 6 * T);  // point x
        vfilter(img, kFG, f.point, y, o + 7 * T);  // point y
        rows[img] = {o, o + T, o + 2 * T, o + 3 * T, o + 4 * T, o + 5 * T, o + 6 * T, o + 7 * T};
      }
      const std::size_t at = static_cast<std::size_t>(y) * w + x0;
      float* out = map.data() + at;
      color.error_row(rows[0], rows[1], f.by_w1, f.by_w2, tw, out);
      const std::uint8_t* m = mask.empty() ? nullptr : mask.data() + at;
      tile_sums[static_cast<std::size_t>(y) * tiles + ti] = detail::row_sum(out, m, tw);
    }
  });

  double total = 0;
  for (double s : tile_sums) total += s;  // fixed order: same result for any thread count
  const std::size_t n = detail::mask_count(mask, w, h);
  result.mean = n ? total / static_cast<double>(n) : std::nan("");
  result.median = detail::median(map, mask);
  if (options.want_map) result.map = std::move(map);
  return result;
}

}  // namespace terrasprite::quality
