// SPDX-License-Identifier: MIT
// The one cache entry format: an entry reads back only under the key it was
// written for, intact; every single flipped byte, every truncation and any
// size claim beyond what the caller can use is a miss with a reason, never a
// hit, an exception or an allocation of the claimed size.
#include "terrasprite/common/cache_entry.h"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <vector>

#include "test_util.h"

namespace ts = terrasprite;

namespace {

const std::string kKey = "terrasprite test entry of model 0123 lod-r0.5";

std::string some_payload() {
  std::string p;
  for (int i = 0; i < 3000; ++i) p += char(i * 7 % 251);
  return p;
}

TEST(CacheEntry, ReadsBackUnderItsKeyOnly) {
  const std::string payload = some_payload();
  const std::string e = ts::encode_cache_entry(kKey, payload);
  const ts::CacheEntryRead ok = ts::decode_cache_entry(e, kKey, payload.size());
  ASSERT_TRUE(ok.payload) << ok.problem;
  EXPECT_EQ(*ok.payload, payload);
  for (const std::string& other :
       std::vector<std::string>{kKey + "x", kKey.substr(1), std::string(), "model 4567"}) {
    const ts::CacheEntryRead r = ts::decode_cache_entry(e, other, payload.size());
    EXPECT_FALSE(r.payload) << other;
    EXPECT_NE(r.problem.find("other inputs"), std::string::npos) << r.problem;
  }
  EXPECT_TRUE(ts::decode_cache_entry(ts::encode_cache_entry(kKey, ""), kKey, 0).payload);
}

// Cost: about 0.1 s (a decode per bit tried of a 3 KB entry). A few bits
// the zstd format ignores (the frame header's unused bit, reserved bits of
// a block) still decode to the very same payload; every other flip is a
// miss with a reason, never a different payload.
TEST(CacheEntry, EveryFlippedByteAndEveryTruncationIsAMiss) {
  const std::string payload = some_payload();
  const std::string e = ts::encode_cache_entry(kKey, payload);
  int same = 0;
  for (std::size_t i = 0; i < e.size(); ++i)
    for (const int bit : {0x01, 0x10, 0x80}) {
      std::string bad = e;
      bad[i] = char(bad[i] ^ bit);
      const ts::CacheEntryRead r = ts::decode_cache_entry(bad, kKey, 1 << 20);
      if (r.payload) {
        EXPECT_EQ(*r.payload, payload) << "byte " << i << " of " << e.size();
        ++same;
      } else {
        EXPECT_FALSE(r.problem.empty()) << i;
      }
    }
  EXPECT_LE(same, 4) << "of " << 3 * e.size() << " flips";
  for (std::size_t i = e.size() - 4; i < e.size(); ++i) {  // the checksum itself
    std::string bad = e;
    bad[i] = char(bad[i] ^ 0x01);
    const ts::CacheEntryRead r = ts::decode_cache_entry(bad, kKey, 1 << 20);
    EXPECT_FALSE(r.payload);
    EXPECT_NE(r.problem.find("checksum"), std::string::npos) << r.problem;
  }
  for (std::size_t n = 0; n < e.size(); ++n)
    EXPECT_FALSE(ts::decode_cache_entry(e.substr(0, n), kKey, 1 << 20).payload) << n;
  EXPECT_FALSE(ts::decode_cache_entry(e + '\0', kKey, 1 << 20).payload) << "a byte after it";
}

// The size field sits after the key: claims of a terabyte, of 4 GB, of
// zstd's "unknown" and "error" sizes, with the frame left as it was.
TEST(CacheEntry, ASizeClaimBeyondTheCallersBoundIsRefusedBeforeDecoding) {
  const std::string payload = some_payload();
  const std::string e = ts::encode_cache_entry(kKey, payload);
  const std::size_t at = 8 + 4 + 4 + kKey.size();
  for (const std::uint64_t claim :
       {std::uint64_t(1) << 40, std::uint64_t(4) << 30, ~std::uint64_t(0), ~std::uint64_t(0) - 1}) {
    std::string bad = e;
    std::memcpy(bad.data() + at, &claim, 8);
    const ts::CacheEntryRead r = ts::decode_cache_entry(bad, kKey, 1 << 20);
    EXPECT_FALSE(r.payload);
    EXPECT_NE(r.problem.find("claims"), std::string::npos) << r.problem;
    // Within the bound but not what the frame holds.
    EXPECT_FALSE(ts::decode_cache_entry(bad, kKey, ~std::uint64_t(0)).payload);
  }
  EXPECT_FALSE(ts::decode_cache_entry(e, kKey, payload.size() - 1).payload)
      << "one byte more than the caller can use";
}

TEST(CacheEntry, FilesMissingOversizedOrNotFilesAreMissesNotErrors) {
  tstest::TempDir t;
  std::filesystem::create_directories(t.path);
  const auto file = t.path / "e.rep";
  EXPECT_FALSE(ts::read_cache_entry(file, kKey, 100).payload);
  EXPECT_TRUE(ts::read_cache_entry(file, kKey, 100).problem.empty()) << "absent: no note";

  const std::string payload = some_payload();
  std::ofstream(file, std::ios::binary) << ts::encode_cache_entry(kKey, payload);
  EXPECT_EQ(ts::read_cache_entry(file, kKey, payload.size()).payload, payload);

  // A sparse terabyte file is refused by its size, unread.
  std::filesystem::resize_file(file, std::uintmax_t(1) << 40);
  const ts::CacheEntryRead big = ts::read_cache_entry(file, kKey, payload.size());
  EXPECT_FALSE(big.payload);
  EXPECT_NE(big.problem.find("more than such an entry holds"), std::string::npos) << big.problem;
  std::filesystem::remove(file);

  std::filesystem::create_directories(file);
  const ts::CacheEntryRead dir = ts::read_cache_entry(file, kKey, payload.size());
  EXPECT_FALSE(dir.payload);
  EXPECT_FALSE(dir.problem.empty());
}

}  // namespace
