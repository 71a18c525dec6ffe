// Uses the installed quality module alone: PSNR and SSIM of two tiny images.
#include <cstdio>

#include "terrasprite/quality/quality.h"

int main() {
  terrasprite::Image a(32, 32), b(32, 32);
  for (int i = 0; i < 32 * 32 * 4; ++i) {
    a.rgba[i] = std::uint8_t((i * 7) % 251);
    b.rgba[i] = std::uint8_t(a.rgba[i] ^ (i % 13 == 0 ? 4 : 0));
  }
  const double psnr = terrasprite::quality::psnr(a.view(), b.view()).rgb;
  const double same = terrasprite::quality::ssim(a.view(), a.view()).ssim;
  std::printf("quality consumer: PSNR %.2f dB, SSIM(a, a) %.3f\n", psnr, same);
  return psnr > 20 && psnr < 100 && same == 1.0 ? 0 : 1;
}
