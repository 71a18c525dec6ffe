// SPDX-License-Identifier: MIT
// PSNR = 10 log10(255^2 / MSE), on R, G, B together (ffmpeg's 'average' for
// equal-size planes) and on unrounded Rec. 601 luma.
#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>
#include <vector>

#include "quality/planes.h"

namespace terrasprite::quality {

namespace {

struct Sums {
  double rgb = 0, luma = 0;
  std::size_t n = 0;
};

double to_db(double mse) {
  if (mse <= 0) return std::numeric_limits<double>::infinity();
  return 10.0 * std::log10(255.0 * 255.0 / mse);
}

}  // namespace

PsnrResult psnr(const ImageView& reference, const ImageView& test, Mask mask) {
  detail::check_inputs("psnr", reference, test, mask);
  const int w = reference.width;
  // Per-row sums, added in row order afterwards: the result does not depend
  // on how TBB splits the rows.
  std::vector<Sums> rows(reference.height);
  tbb::parallel_for(0, reference.height, [&](int y) {
    const std::uint8_t* a = reference.row(y);
    const std::uint8_t* b = test.row(y);
    const std::uint8_t* m = mask.empty() ? nullptr : mask.data() + static_cast<std::size_t>(y) * w;
    std::int64_t rgb = 0;
    Sums acc;
    for (int x = 0; x < w; ++x) {
      if (m && !m[x]) continue;
      int ar, ag, ab, br, bg, bb;
      detail::rgb_at(a, reference.channels, x, ar, ag, ab);
      detail::rgb_at(b, test.channels, x, br, bg, bb);
      rgb += (ar - br) * (ar - br) + (ag - bg) * (ag - bg) + (ab - bb) * (ab - bb);
      const double d = (0.299 * ar + 0.587 * ag + 0.114 * ab) - (0.299 * br + 0.587 * bg + 0.114 * bb);
      acc.luma += d * d;
      ++acc.n;
    }
    acc.rgb = static_cast<double>(rgb);
    rows[y] = acc;
  });
  Sums s;
  for (const Sums& r : rows) s.rgb += r.rgb, s.luma += r.luma, s.n += r.n;
  if (s.n == 0) return {std::nan(""), std::nan("")};
  return {to_db(s.rgb / (3.0 * s.n)), to_db(s.luma / s.n)};
}

}  // namespace terrasprite::quality
