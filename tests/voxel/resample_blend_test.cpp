// SPDX-License-Identifier: MIT
// The resample's AVX2 blend gives the one-pixel blend's colour and depth bit
// for bit: any subset of the four samples present, sky and surface samples,
// depth spreads either side of the 30 % smooth test, weights 0 and 1, and
// spans that leave a tail. About 1 ms.
#include "voxel/resample_blend.h"

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "common/simd.h"

namespace terrasprite {
namespace {

TEST(ResampleBlend, Avx2MatchesTheScalarBlendBitForBit) {
  if (!simd::has_avx2()) GTEST_SKIP() << "no AVX2 on this CPU";
  std::mt19937 rng(13);
  std::uniform_real_distribution<float> unit(0.f, 1.f), depth(10.f, 5000.f);
  std::vector<PlaneSample> samples(4096);
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const std::uint32_t c = std::uint32_t(rng());
    const int kind = int(rng() % 8);
    // Sky, near-equal depths (smooth), spread depths (a silhouette), zero depth.
    const float d = kind == 0   ? std::numeric_limits<float>::infinity()
                    : kind == 1 ? 0.f
                    : kind < 5  ? 1000.f + float(i % 7)
                                : depth(rng);
    samples[i] = {c, d};
  }
  const std::uint32_t sky = 0xffe1b996u;
  for (int count : {1, 7, 8, 9, 33, 64}) {
    for (int rep = 0; rep < 40; ++rep) {
      ResampleTaps t;
      t.x0 = 3;
      t.count = count;
      for (int i = 0; i < count; ++i) {
        const int pick = int(rng() % 6);
        t.fc[i] = pick == 0 ? 0.f : pick == 1 ? 1.f : unit(rng);
        t.fk[i] = pick == 2 ? 0.f : pick == 3 ? 1.f : unit(rng);
        t.ok[i] = rep == 0 ? 0u : rep == 1 ? 15u : std::uint32_t(rng() % 16);
        for (int a = 0; a < 2; ++a) {
          // Absent samples may carry any index (never read).
          t.at[a][i] = (t.ok[i] >> (2 * a)) & 3u ? std::size_t(rng() % (samples.size() - 1))
                                                 : std::size_t(rng());
        }
      }
      const int w = t.x0 + count;
      std::vector<std::uint8_t> row_s(std::size_t(w) * 4, 7), row_v(std::size_t(w) * 4, 7);
      std::vector<float> dep_s(std::size_t(w), -1.f), dep_v(std::size_t(w), -1.f);
      blend_taps_scalar(t, samples.data(), sky, row_s.data(), dep_s.data());
      ASSERT_TRUE(blend_taps_avx2(t, samples.data(), sky, row_v.data(), dep_v.data()));
      EXPECT_EQ(row_s, row_v) << "count " << count << " rep " << rep;
      EXPECT_EQ(std::memcmp(dep_s.data(), dep_v.data(), dep_s.size() * sizeof(float)), 0)
          << "count " << count << " rep " << rep;
      std::vector<std::uint8_t> row_d(std::size_t(w) * 4, 7);
      std::vector<float> dep_d(std::size_t(w), -1.f);
      blend_taps(t, samples.data(), samples.size(), sky, row_d.data(), dep_d.data());
      EXPECT_EQ(row_s, row_d);
    }
  }
}

}  // namespace
}  // namespace terrasprite
