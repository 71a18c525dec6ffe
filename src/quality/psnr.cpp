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

// One row, channel counts fixed at compile time; the mask enters as a 0/1
// weight rather than a branch, so the loop stays a straight vectorisable sum.
// The luma difference is the weighted sum of the channel differences.
template <int CA, int CB>
Sums row_sums(const std::uint8_t* a, const std::uint8_t* b, const std::uint8_t* m, int w) {
  std::int64_t rgb = 0, n = 0;
  double lum = 0;
  for (int x = 0; x < w; ++x) {
    const std::uint8_t* p = a + static_cast<std::size_t>(x) * CA;
    const std::uint8_t* q = b + static_cast<std::size_t>(x) * CB;
    const int dr = p[0] - q[0], dg = p[CA == 1 ? 0 : 1] - q[CB == 1 ? 0 : 1],
              db = p[CA == 1 ? 0 : 2] - q[CB == 1 ? 0 : 2];
    const int keep = m ? (m[x] != 0) : 1;
    rgb += keep * (dr * dr + dg * dg + db * db);
    const double d = 0.299 * dr + 0.587 * dg + 0.114 * db;
    lum += keep * (d * d);
    n += keep;
  }
  return {static_cast<double>(rgb), lum, static_cast<std::size_t>(n)};
}

template <int CA>
Sums row_sums(const std::uint8_t* a, const std::uint8_t* b, int cb, const std::uint8_t* m, int w) {
  switch (cb) {
    case 1:
      return row_sums<CA, 1>(a, b, m, w);
    case 3:
      return row_sums<CA, 3>(a, b, m, w);
    default:
      return row_sums<CA, 4>(a, b, m, w);
  }
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
    switch (reference.channels) {
      case 1:
        rows[y] = row_sums<1>(a, b, test.channels, m, w);
        break;
      case 3:
        rows[y] = row_sums<3>(a, b, test.channels, m, w);
        break;
      default:
        rows[y] = row_sums<4>(a, b, test.channels, m, w);
        break;
    }
  });
  Sums s;
  for (const Sums& r : rows) s.rgb += r.rgb, s.luma += r.luma, s.n += r.n;
  if (s.n == 0) return {std::nan(""), std::nan("")};
  return {to_db(s.rgb / (3.0 * s.n)), to_db(s.luma / s.n)};
}

}  // namespace terrasprite::quality
