// SPDX-License-Identifier: MIT
// PSNR, SSIM, MS-SSIM: tiny cases, identity, symmetry, monotonic degradation,
// masks and bad input.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>

#include "quality_test_util.h"
#include "terrasprite/common/error.h"
#include "terrasprite/quality/quality.h"

namespace terrasprite::quality {
namespace {

using testing::blurred;
using testing::flat;
using testing::noisy;
using testing::scene;

TEST(Psnr, KnownValueOnFlatImages) {
  const Image a = flat(8, 8, {100, 100, 100}), b = flat(8, 8, {110, 100, 100});
  // MSE over R, G, B = 100 / 3; luma differs by 0.299 * 10.
  const PsnrResult p = psnr(a.view(), b.view());
  EXPECT_NEAR(p.rgb, 10 * std::log10(255.0 * 255.0 / (100.0 / 3)), 1e-9);
  EXPECT_NEAR(p.luma, 10 * std::log10(255.0 * 255.0 / (2.99 * 2.99)), 1e-9);
}

TEST(Psnr, IdentityIsInfiniteAndOnePixelWorks) {
  const Image a = flat(1, 1, {1, 2, 3});
  const PsnrResult p = psnr(a.view(), a.view());
  EXPECT_TRUE(std::isinf(p.rgb) && p.rgb > 0);
  EXPECT_TRUE(std::isinf(p.luma) && p.luma > 0);
}

TEST(Psnr, GreyViewEqualsReplicatedRgb) {
  const Image a = scene(40, 30), b = noisy(a, 10);
  std::vector<std::uint8_t> ga(40 * 30), gb(40 * 30);
  for (int i = 0; i < 40 * 30; ++i) ga[i] = a.rgba[4 * i + 1], gb[i] = b.rgba[4 * i + 1];
  Image ra = a, rb = b;
  for (int i = 0; i < 40 * 30; ++i)
    for (int c = 0; c < 3; ++c) ra.rgba[4 * i + c] = ga[i], rb.rgba[4 * i + c] = gb[i];
  const ImageView va{ga, 40, 30, 40, 1}, vb{gb, 40, 30, 40, 1};
  EXPECT_DOUBLE_EQ(psnr(va, vb).rgb, psnr(ra.view(), rb.view()).rgb);
}

TEST(Metrics, TinyImagesWork) {
  // FLIP's filters are wider than these images: edges replicate.
  for (int n : {1, 2, 3}) {
    const Image a = flat(n, n, {10, 200, 30}), b = flat(n, n, {12, 190, 40});
    const FlipResult f = flip(a.view(), b.view());
    EXPECT_GT(f.mean, 0.0);
    EXPECT_DOUBLE_EQ(f.mean, f.median);  // flat: every pixel the same
    EXPECT_TRUE(std::isfinite(psnr(a.view(), b.view()).rgb));
  }
}

TEST(Metrics, ChannelCountsAndStridesDoNotMatter) {
  const int w = 37, h = 29, stride = 3 * w + 5;
  const Image a = scene(w, h), b = noisy(a, 9);
  // The test image as tightly packed RGBA and as padded RGB rows.
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(stride) * h, 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) rgb[y * stride + 3 * x + c] = b.px(x, y)[c];
  const ImageView vb{rgb, w, h, stride, 3};
  EXPECT_EQ(psnr(a.view(), b.view()).luma, psnr(a.view(), vb).luma);
  EXPECT_EQ(ssim(a.view(), b.view()).ssim, ssim(a.view(), vb).ssim);
  SsimOptions ff;
  ff.mode = SsimMode::kFfmpeg;
  EXPECT_EQ(ssim(a.view(), b.view(), ff).ssim, ssim(a.view(), vb, ff).ssim);
  EXPECT_EQ(flip(a.view(), b.view()).mean, flip(a.view(), vb).mean);
}

TEST(Metrics, SymmetricWhereTheDefinitionIs) {
  const Image a = scene(96, 80), b = noisy(blurred(a, 1), 6);
  EXPECT_DOUBLE_EQ(psnr(a.view(), b.view()).rgb, psnr(b.view(), a.view()).rgb);
  EXPECT_NEAR(ssim(a.view(), b.view()).ssim, ssim(b.view(), a.view()).ssim, 1e-12);
  SsimOptions ff;
  ff.mode = SsimMode::kFfmpeg;
  EXPECT_NEAR(ssim(a.view(), b.view(), ff).ssim, ssim(b.view(), a.view(), ff).ssim, 1e-12);
  // FLIP is symmetric too: every term uses |difference|.
  EXPECT_NEAR(flip(a.view(), b.view()).mean, flip(b.view(), a.view()).mean, 1e-6);
}

TEST(Metrics, IdentityGivesPerfectScores) {
  const Image a = scene(200, 180);
  const SsimResult s = ssim(a.view(), a.view());
  EXPECT_DOUBLE_EQ(s.ssim, 1.0);
  for (double c : s.channels) EXPECT_DOUBLE_EQ(c, 1.0);
  SsimOptions ff;
  ff.mode = SsimMode::kFfmpeg;
  EXPECT_DOUBLE_EQ(ssim(a.view(), a.view(), ff).ssim, 1.0);
  EXPECT_NEAR(msssim(a.view(), a.view()), 1.0, 1e-12);
  const FlipResult f = flip(a.view(), a.view());
  EXPECT_EQ(f.mean, 0.0);
  EXPECT_EQ(f.median, 0.0);
}

TEST(Metrics, DegradeMonotonicallyWithNoiseAndBlur) {
  const Image a = scene(192, 180);
  double last_psnr = INFINITY, last_ssim = 1, last_ms = 1, last_flip = 0;
  for (double sigma : {2.0, 6.0, 15.0, 35.0}) {
    const Image b = noisy(a, sigma);
    const double p = psnr(a.view(), b.view()).rgb, s = ssim(a.view(), b.view()).ssim;
    const double m = msssim(a.view(), b.view()), f = flip(a.view(), b.view()).mean;
    EXPECT_LT(p, last_psnr) << sigma;
    EXPECT_LT(s, last_ssim) << sigma;
    EXPECT_LT(m, last_ms) << sigma;
    EXPECT_GT(f, last_flip) << sigma;
    last_psnr = p, last_ssim = s, last_ms = m, last_flip = f;
  }
  last_psnr = INFINITY, last_ssim = 1, last_ms = 1, last_flip = 0;
  for (int passes : {1, 2, 4, 8}) {
    const Image b = blurred(a, passes);
    const double p = psnr(a.view(), b.view()).rgb, s = ssim(a.view(), b.view()).ssim;
    const double m = msssim(a.view(), b.view()), f = flip(a.view(), b.view()).mean;
    EXPECT_LT(p, last_psnr) << passes;
    EXPECT_LT(s, last_ssim) << passes;
    EXPECT_LT(m, last_ms) << passes;
    EXPECT_GT(f, last_flip) << passes;
    last_psnr = p, last_ssim = s, last_ms = m, last_flip = f;
  }
}

TEST(Metrics, SameResultForOneAndTwoThreads) {
  const Image a = scene(300, 170), b = noisy(a, 9);
  double s2, f2, m2;
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    s2 = ssim(a.view(), b.view()).ssim, f2 = flip(a.view(), b.view()).mean,
    m2 = psnr(a.view(), b.view()).luma;
  }
  EXPECT_EQ(s2, ssim(a.view(), b.view()).ssim);
  EXPECT_EQ(f2, flip(a.view(), b.view()).mean);
  EXPECT_EQ(m2, psnr(a.view(), b.view()).luma);
}

TEST(Masks, ScoreOnlyTheSelectedPixels) {
  const int w = 120, h = 100;
  const Image a = scene(w, h);
  Image b = a;
  // Damage only the right half; a mask of the left half sees perfect images.
  Image damaged = noisy(a, 20);
  for (int y = 0; y < h; ++y)
    for (int x = w / 2; x < w; ++x)
      for (int c = 0; c < 3; ++c) b.px(x, y)[c] = damaged.px(x, y)[c];
  std::vector<std::uint8_t> left(w * h, 0), right(w * h, 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      left[y * w + x] = x < w / 2 - 12;  // clear of the damage by more than any filter radius
      right[y * w + x] = x >= w / 2;
    }
  EXPECT_TRUE(std::isinf(psnr(a.view(), b.view(), left).rgb));
  EXPECT_DOUBLE_EQ(ssim(a.view(), b.view(), {}, left).ssim, 1.0);
  SsimOptions ff;
  ff.mode = SsimMode::kFfmpeg;
  EXPECT_DOUBLE_EQ(ssim(a.view(), b.view(), ff, left).ssim, 1.0);
  EXPECT_EQ(flip(a.view(), b.view(), {}, left).mean, 0.0);
  // The damaged half alone scores worse than the whole image.
  EXPECT_LT(psnr(a.view(), b.view(), right).rgb, psnr(a.view(), b.view()).rgb);
  EXPECT_LT(ssim(a.view(), b.view(), {}, right).ssim, ssim(a.view(), b.view()).ssim);
  EXPECT_GT(flip(a.view(), b.view(), {}, right).mean, flip(a.view(), b.view()).mean);
  // Empty selection: no score rather than a made-up one.
  const std::vector<std::uint8_t> none(w * h, 0);
  EXPECT_TRUE(std::isnan(psnr(a.view(), b.view(), none).rgb));
  EXPECT_TRUE(std::isnan(ssim(a.view(), b.view(), {}, none).ssim));
  EXPECT_TRUE(std::isnan(flip(a.view(), b.view(), {}, none).mean));
}

TEST(Masks, MsssimMaskOfDamagedRegion) {
  const Image a = scene(200, 190);
  const Image b = noisy(a, 12);
  std::vector<std::uint8_t> all(200 * 190, 1);
  EXPECT_DOUBLE_EQ(msssim(a.view(), b.view(), all), msssim(a.view(), b.view()));
}

TEST(BadInput, ThrowsWithClearMessages) {
  const Image a = scene(64, 64), b = scene(64, 65), tiny = scene(10, 10), empty;
  auto message = [](auto&& f) {
    try {
      f();
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no throw");
  };
  EXPECT_EQ(message([&] { psnr(a.view(), b.view()); }),
            "psnr: images differ in size: reference 64x64, test 64x65");
  EXPECT_NE(message([&] { ssim(a.view(), b.view()); }).find("differ in size"), std::string::npos);
  EXPECT_NE(message([&] { flip(a.view(), b.view()); }).find("differ in size"), std::string::npos);
  EXPECT_NE(message([&] { psnr(empty.view(), empty.view()); }).find("empty"), std::string::npos);
  EXPECT_NE(message([&] { ssim(tiny.view(), tiny.view()); }).find("11x11"), std::string::npos);
  EXPECT_NE(message([&] { msssim(a.view(), a.view()); }).find("at least 176"), std::string::npos);
  const std::vector<std::uint8_t> short_mask(10, 1);
  EXPECT_NE(message([&] { psnr(a.view(), a.view(), short_mask); }).find("mask has 10 bytes"),
            std::string::npos);
  FlipOptions bad;
  bad.ppd = -1;
  EXPECT_NE(message([&] { flip(a.view(), a.view(), bad); }).find("pixels per degree"),
            std::string::npos);
}

TEST(Ssim, DownsampleOptionUsesWangsFactor) {
  // 300 px: f = round(300 / 256) = 1, so the option changes nothing.
  const Image a = scene(300, 300), b = noisy(a, 10);
  SsimOptions d;
  d.downsample = true;
  EXPECT_DOUBLE_EQ(ssim(a.view(), b.view(), d).ssim, ssim(a.view(), b.view()).ssim);
  // 520 px: f = 2, and averaging 2x2 removes much of the noise.
  const Image c = scene(520, 520), e = noisy(c, 10);
  EXPECT_GT(ssim(c.view(), e.view(), d).ssim, ssim(c.view(), e.view()).ssim + 0.01);
}

TEST(Difference, ScaledAbsoluteDifferenceAndFlipImage) {
  const Image a = flat(4, 3, {10, 20, 30}), b = flat(4, 3, {12, 20, 100});
  const Image d = difference_image(a.view(), b.view(), 4);
  EXPECT_EQ(d.px(2, 1)[0], 8);
  EXPECT_EQ(d.px(2, 1)[1], 0);
  EXPECT_EQ(d.px(2, 1)[2], 255);  // 70 * 4 clamped
  EXPECT_EQ(d.px(2, 1)[3], 255);
  const std::vector<float> map = {0.0f, 1.0f};
  const Image m = flip_image(map, 2, 1);
  EXPECT_LT(m.px(0, 0)[0] + m.px(0, 0)[1], 5);  // magma starts black
  EXPECT_GT(m.px(1, 0)[0], 240);                // and ends in a pale yellow
  EXPECT_THROW(flip_image(map, 3, 1), InputError);
}

}  // namespace
}  // namespace terrasprite::quality
