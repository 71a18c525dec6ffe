// TEMPORARY local stub until branch `quality` lands. NOT COMMITTED.
#include <cmath>
#include "terrasprite/quality.h"
namespace terrasprite::quality {
static double mse(const ImageView& a, const ImageView& b) {
  double s = 0; long n = 0;
  for (int y = 0; y < a.height; ++y) for (int x = 0; x < a.width; ++x) for (int c = 0; c < 3; ++c) {
    double d = double(a.row(y)[x * a.channels + c]) - b.row(y)[x * b.channels + c]; s += d * d; ++n; }
  return s / n;
}
PsnrResult psnr(const ImageView& a, const ImageView& b, Mask) { double m = mse(a, b); double p = m == 0 ? INFINITY : 10 * std::log10(65025.0 / m); return {p, p}; }
SsimResult ssim(const ImageView& a, const ImageView& b, const SsimOptions&, Mask) { SsimResult r; r.ssim = 1.0 / (1.0 + mse(a, b) / 100.0); return r; }
double msssim(const ImageView& a, const ImageView& b) { return ssim(a, b).ssim; }
FlipResult flip(const ImageView& a, const ImageView& b, const FlipOptions&, Mask) { FlipResult r; r.mean = std::sqrt(mse(a, b)) / 255; return r; }
}
