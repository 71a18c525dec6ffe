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
// row by row while the ring is in cache. Borders reflect (d c b a | a b c d).
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
#include "terrasprite/error.h"

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
    k.w[i] = static_cast<float>(h[i] > 0 ? (pos > 0 ? h[i] / pos : 0) : (neg < 0 ? -h[i] / neg : 0));
  return k;
}

struct Filters {
  Kernel a, rg, by1, by2;  // CSF: achromatic, red-green, blue-yellow (two terms)
  float by_w1 = 1, by_w2 = 0;
  Kernel gauss, edge, point;  // feature detectors: x-derivative factor times Gaussian in y
  int radius = 0;

  explicit Filters(double ppd) {
    // CSF parameters (a1, b1, a2, b2) of the paper; b in degrees^2.
    constexpr double b_a = 0.0047, b_rg = 0.0053, a1_by = 34.1, b1_by = 0.04, a2_by = 13.5, b2_by = 0.025;
    // One radius for all channels, from the widest term: 3 standard deviations.
    const int r = static_cast<int>(std::ceil(3 * std::sqrt(b1_by / (2 * std::numbers::pi * std::numbers::pi)) * ppd));
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
    edge = signed_normalised(he);
    point = signed_normalised(hp);
    radius = std::max({a.radius, rg.radius, by1.radius, by2.radius, fr});
  }
};

// Horizontal planes per image, in ring order.
enum HPlane { kA, kRG, kBY1, kBY2, kFG, kFE, kFP, kHPlanes };

}  // namespace

FlipResult flip(const ImageView& reference, const ImageView& test, const FlipOptions& options, Mask mask) {
  detail::check_inputs("flip", reference, test, mask);
  if (!std::isfinite(options.ppd) || options.ppd <= 0 || options.ppd > 1000)
    throw InputError(fmt::format("flip: pixels per degree must be in (0, 1000], got {}", options.ppd));
  const int w = reference.width, h = reference.height;
  const Filters f(options.ppd);
  const detail::FlipColor& color = detail::flip_color();
  const int R = f.radius, K = 2 * R + 1;
  const ImageView* images[2] = {&reference, &test};

  FlipResult result;
  std::vector<float> map(static_cast<std::size_t>(w) * h);
  std::vector<double> row_sums(h, 0.0);

  // Bands: a few per thread for balance, tall enough that the 2R extra rows a
  // band filters at its edges stay a small overhead.
  const int threads = tbb::this_task_arena::max_concurrency();
  const int band = std::max(16, (h + 4 * threads - 1) / (4 * threads));
  const int bands = (h + band - 1) / band;
  tbb::parallel_for(0, bands, [&](int bi) {
    const int y0 = bi * band, y1 = std::min(h, y0 + band);
    const std::size_t W = static_cast<std::size_t>(w);
    std::vector<float> ring(2 * kHPlanes * K * W);
    auto slot = [&](int img, int plane, int v) {  // v: virtual row, y0 - R <= v < y1 + R
      return ring.data() + ((static_cast<std::size_t>(img) * kHPlanes + plane) * K + (v - y0 + R) % K) * W;
    };
    const std::size_t P = W + 2 * R;  // padded input row
    std::vector<float> in(4 * P);     // Yy, Cx, Cz, luminance
    std::vector<float> vert(2 * 8 * W);
    std::vector<const float*> ptr(K);

    auto vfilter = [&](int img, int plane, const Kernel& k, int y, float* out) {
      for (int i = 0; i < k.taps(); ++i) ptr[i] = slot(img, plane, y - k.radius + i);
      detail::filter_column(ptr.data(), k.taps(), k.w.data(), w, out);
    };
    auto hfilter = [&](const float* padded, const Kernel& k, float* out) {
      detail::filter_row(padded + (R - k.radius), w, k.w.data(), k.taps(), out);
    };

    for (int v = y0 - R; v < y1 + R; ++v) {
      const int sy = detail::reflect(v, h);
      for (int img = 0; img < 2; ++img) {
        const ImageView& im = *images[img];
        color.to_ycxcz_row(im.row(sy), im.channels, w, in.data() + R, in.data() + P + R, in.data() + 2 * P + R,
                           in.data() + 3 * P + R);
        for (int c = 0; c < 4; ++c) {
          float* row = in.data() + c * P;
          for (int i = 0; i < R; ++i) row[i] = row[R + detail::reflect(i - R, w)];
          for (int i = 0; i < R; ++i) row[R + w + i] = row[R + detail::reflect(w + i, w)];
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
        float* o = vert.data() + img * 8 * W;
        vfilter(img, kA, f.a, y, o);
        vfilter(img, kRG, f.rg, y, o + W);
        vfilter(img, kBY1, f.by1, y, o + 2 * W);
        vfilter(img, kBY2, f.by2, y, o + 3 * W);
        vfilter(img, kFE, f.gauss, y, o + 4 * W);  // edge x: d/dx then Gaussian in y
        vfilter(img, kFG, f.edge, y, o + 5 * W);   // edge y
        vfilter(img, kFP, f.gauss, y, o + 6 * W);  // point x
        vfilter(img, kFG, f.point, y, o + 7 * W);  // point y
        rows[img] = {o, o + W, o + 2 * W, o + 3 * W, o + 4 * W, o + 5 * W, o + 6 * W, o + 7 * W};
      }
      float* out = map.data() + static_cast<std::size_t>(y) * W;
      color.error_row(rows[0], rows[1], f.by_w1, f.by_w2, w, out);
      const std::uint8_t* m = mask.empty() ? nullptr : mask.data() + static_cast<std::size_t>(y) * W;
      double sum = 0;
      for (int x = 0; x < w; ++x) sum += (m && !m[x]) ? 0.0 : out[x];
      row_sums[y] = sum;
    }
  });

  double total = 0;
  for (double s : row_sums) total += s;
  const std::size_t n = detail::mask_count(mask, w, h);
  result.mean = n ? total / static_cast<double>(n) : std::nan("");
  result.median = detail::median(map, mask);
  if (options.want_map) result.map = std::move(map);
  return result;
}

}  // namespace terrasprite::quality
