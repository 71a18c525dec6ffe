// SPDX-License-Identifier: MIT
// The on-disk representation cache: a second GlModel over the same cache
// reads the LOD chain and both impostors instead of building them and draws
// the very same pixels; another build parameter is another entry; a damaged
// entry is reported, rebuilt and replaced; a disabled cache writes nothing.
#include "terrasprite/objects/representation_cache.h"

#include <gtest/gtest.h>
#include <zstd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "gl/render_target.h"
#include "object_test_util.h"
#include "terrasprite/gl/gl_context.h"
#include "terrasprite/objects/object_renderer.h"
#include "test_util.h"

namespace ts = terrasprite;
namespace fs = std::filesystem;

namespace {

constexpr int kSize = 96;

class RepresentationCaching : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = fs::path(::testing::TempDir()) /
          ("repcache_" +
           std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir);
  }
  void TearDown() override { fs::remove_all(dir); }

  ts::RepresentationCache cache() const { return ts::RepresentationCache(dir, "0123abcd", "box"); }

  // The box drawn with `rep` by a fresh GlModel over `c`, seen obliquely.
  ts::Image draw(const ts::RepresentationCache& c, const ts::Representation& rep) {
    return draw_model(box, c, rep);
  }
  ts::Image draw_model(const ts::Model& model, const ts::RepresentationCache& c,
                       const ts::Representation& rep) {
    ts::GlModel m(model, ts::cached_lod_chain(model, {}, c), c);
    m.prepare(rep);
    target.bind_and_clear();
    const ts::ObjectInstance at_origin{};
    m.draw(rep, std::span(&at_origin, 1), tstest::orbit(glm::dvec3(model.center()), 20.0, 30, 35));
    glFinish();
    return target.read_color();
  }

  std::size_t files() const {
    std::size_t n = 0;
    if (fs::exists(dir))
      for (const auto& e : fs::directory_iterator(dir)) n += e.is_regular_file();
    return n;
  }

  fs::path dir;
  ts::Model box = tstest::colored_box(1.f, 2.f, 1.5f);
  ts::GlContext ctx;
  ts::gl::RenderTarget target{kSize, kSize};
  const ts::Representation relief{ts::ObjectKind::kRelief, 0, 32};
  const ts::Representation oct{ts::ObjectKind::kOctahedral, 0, 32, 4};
};

TEST_F(RepresentationCaching, SecondModelReadsEverythingAndDrawsTheSamePixels) {
  const ts::RepresentationCache first = cache();
  const ts::Image relief_built = draw(first, relief), oct_built = draw(first, oct);
  // Two chains (one per draw: the second reads the first's) and two impostors.
  EXPECT_EQ(first.stats().misses, 3);
  EXPECT_EQ(first.stats().hits, 1);
  EXPECT_EQ(files(), 3u);

  const ts::RepresentationCache second = cache();
  const ts::Image relief_read = draw(second, relief), oct_read = draw(second, oct);
  EXPECT_EQ(second.stats().misses, 0);
  EXPECT_EQ(second.stats().hits, 4);
  EXPECT_EQ(relief_read.rgba, relief_built.rgba);
  EXPECT_EQ(oct_read.rgba, oct_built.rgba);
  // The images are of the box, not of an empty texture.
  EXPECT_NE(relief_read.rgba, draw(ts::RepresentationCache{}, ts::Representation{}).rgba);

  const ts::LodOptions finer{.ratio = 0.7};
  const ts::RepresentationCache third = cache();
  (void)ts::cached_lod_chain(box, finer, third);
  EXPECT_EQ(third.stats().misses, 1) << "another LOD ratio must be another entry";
}

TEST(LodChainKey, EveryOptionThatChangesTheLevelsChangesTheKey) {
  // Quality tables key on it too: a table measured on other levels is stale.
  const std::string base = ts::lod_chain_key({});
  EXPECT_EQ(ts::lod_chain_key({}), base);
  EXPECT_NE(ts::lod_chain_key({.ratio = 0.7}), base);
  EXPECT_NE(ts::lod_chain_key({.min_fraction = 0.02}), base);
  EXPECT_NE(ts::lod_chain_key({.min_triangles = 8}), base);
  EXPECT_NE(ts::lod_chain_key({.crease_deg = 30}), base);
}

TEST_F(RepresentationCaching, DamagedEntryIsRebuiltAndReplaced) {
  const ts::Image built = draw(cache(), relief);
  const fs::path file = cache().file("relief-32");
  ASSERT_TRUE(fs::is_regular_file(file));
  const auto size = fs::file_size(file);
  fs::resize_file(file, size / 2);  // an interrupted copy, a full disk

  const ts::RepresentationCache damaged = cache();
  testing::internal::CaptureStderr();
  const ts::Image rebuilt = draw(damaged, relief);
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("relief-32"), std::string::npos) << err;
  EXPECT_NE(err.find("truncated"), std::string::npos) << err;
  EXPECT_EQ(damaged.stats().rejected, 1);
  EXPECT_EQ(rebuilt.rgba, built.rgba);
  EXPECT_EQ(fs::file_size(file), size) << "the rebuilt entry replaces the damaged one";

  // Flipped payload bytes fail the checksum.
  {
    std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(std::streamoff(size - 10));
    f.write("garbage!", 8);
  }
  const ts::RepresentationCache flipped = cache();
  testing::internal::CaptureStderr();
  EXPECT_EQ(draw(flipped, relief).rgba, built.rgba);
  EXPECT_NE(testing::internal::GetCapturedStderr().find("checksum"), std::string::npos);
  EXPECT_EQ(flipped.stats().rejected, 1);
}

// An entry claiming more than the caller's bound (a terabyte, or 4 GB of an
// impostor's few kilobytes) is refused before decoding: one warning, then
// rebuilt and replaced, so the next run reads it.
TEST(RepresentationCacheEntry, AnImpossibleSizeIsRefusedNotAllocated) {
  tstest::TempDir dir;
  const ts::RepresentationCache cache(dir.path, "key", "model");
  const std::string payload(1000, 'x');
  cache.write("what", payload);
  ASSERT_EQ(cache.read("what", payload.size()), payload);
  testing::internal::CaptureStderr();
  EXPECT_FALSE(cache.read("what", payload.size() - 1));
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("claims 1000 bytes"), std::string::npos) << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  EXPECT_EQ(cache.stats().rejected, 1);
}

// Entries are found by file name but read only under the key they record:
// model A's entries copied under model B's names (same file stem, same
// entry names) are refused and B's own are built. Every representation
// (the LOD chain, a relief impostor of the very same size) is checked.
TEST_F(RepresentationCaching, AnotherModelsEntriesAreNeverRead) {
  const ts::Model other = tstest::colored_box(2.f, 1.f, 0.5f);
  const ts::RepresentationCache a(dir, ts::model_source_key(box, {}), "model");
  const ts::RepresentationCache b(dir, ts::model_source_key(other, {}), "model");
  ASSERT_NE(ts::model_source_key(box, {}), ts::model_source_key(other, {}));
  EXPECT_EQ(ts::model_source_key(box, {}),
            ts::model_source_key(tstest::colored_box(1.f, 2.f, 1.5f), {}))
      << "the same content is the same key";
  (void)draw(a, relief);
  const ts::Image b_built = draw(ts::RepresentationCache{}, relief);  // no cache: built

  // B's entry names now hold A's bytes.
  for (const std::string& what : std::vector<std::string>{ts::lod_chain_key({}), "relief-32"})
    fs::copy_file(a.file(what), b.file(what), fs::copy_options::overwrite_existing);
  testing::internal::CaptureStderr();
  ts::GlModel gb(other, ts::cached_lod_chain(other, {}, b), b);
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_EQ(b.stats().hits, 0);
  EXPECT_EQ(b.stats().rejected, 1) << err;
  EXPECT_NE(err.find("other inputs"), std::string::npos) << err;
  EXPECT_EQ(gb.chain().front().positions, ts::build_lod_chain(other).front().positions);

  testing::internal::CaptureStderr();
  const ts::Image b_read = draw_model(other, b, relief);
  testing::internal::GetCapturedStderr();
  EXPECT_EQ(b.stats().hits, 1) << "B's chain, rebuilt, is read back";
  EXPECT_EQ(b.stats().rejected, 2) << "A's relief impostor is refused";
  EXPECT_EQ(b_read.rgba, draw_model(other, ts::RepresentationCache{}, relief).rgba);
  EXPECT_NE(b_read.rgba, b_built.rgba) << "B's impostor, not the box's";
}

TEST_F(RepresentationCaching, DisabledCacheWritesNothing) {
  const ts::RepresentationCache off;
  (void)draw(off, oct);
  EXPECT_FALSE(fs::exists(dir));
  EXPECT_EQ(off.stats().hits + off.stats().misses, 0);
}

TEST(LodChainBytes, RoundTripAndRejectOutOfRangeIndices) {
  const ts::Model box = tstest::colored_box();
  const std::vector<ts::LodLevel> chain = ts::build_lod_chain(box);
  const std::string bytes = ts::serialize_lod_chain(chain);
  const auto back = ts::deserialize_lod_chain(bytes, box.materials.size());
  ASSERT_TRUE(back.has_value());
  ASSERT_EQ(back->size(), chain.size());
  for (std::size_t i = 0; i < chain.size(); ++i) {
    EXPECT_EQ((*back)[i].indices, chain[i].indices);
    EXPECT_EQ((*back)[i].positions, chain[i].positions);
    EXPECT_EQ((*back)[i].error_m, chain[i].error_m);
  }
  std::vector<ts::LodLevel> bad = chain;
  bad[0].indices[0] = std::uint32_t(bad[0].positions.size());
  EXPECT_FALSE(ts::deserialize_lod_chain(ts::serialize_lod_chain(bad), box.materials.size()));
  EXPECT_FALSE(ts::deserialize_lod_chain(bytes, 1)) << "a part's material beyond the model's";
  EXPECT_FALSE(ts::deserialize_lod_chain(bytes.substr(0, bytes.size() - 1), box.materials.size()));
}

}  // namespace
