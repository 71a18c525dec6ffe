// SPDX-License-Identifier: MIT
// The quality table cache: an entry is read only for the model content and
// options it was measured with, intact; another model's entry under this
// model's file name, a damaged one or one of other options is a miss with
// one note, never a table served for the wrong model. Cost: well under 0.1 s.
#include "terrasprite/objects/quality_table_cache.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>

#include "object_test_util.h"
#include "terrasprite/objects/quality_table_json.h"
#include "terrasprite/objects/representation_cache.h"
#include "test_util.h"

namespace ts = terrasprite;
namespace fs = std::filesystem;

namespace {

struct TableCaching : ::testing::Test {
  tstest::TempDir t;
  ts::Model a = tstest::colored_box(1.f, 2.f, 1.5f), b = tstest::colored_box(2.f, 1.f, 0.5f);
  ts::TableOptions o;
  std::string chain = ts::lod_chain_key({});

  ts::TableCacheEntry entry(const ts::Model& m, const std::string& file,
                            const ts::TableOptions& opt) const {
    return ts::table_cache_entry(t.path.string(), file, m, {}, opt, chain);
  }
  static std::string note_of(const std::function<void()>& f) {
    testing::internal::CaptureStderr();
    f();
    return testing::internal::GetCapturedStderr();
  }
};

TEST_F(TableCaching, AnotherModelsTableIsNeverServed) {
  const ts::TableCacheEntry ea = entry(a, "one/model.obj", o), eb = entry(b, "two/model.obj", o);
  EXPECT_NE(ea.key, eb.key);
  ts::QualityTable table;
  table.model = "model A";
  ts::write_table_cache(ea, ts::table_json(table, o));
  ASSERT_TRUE(ts::read_table_cache(ea));
  EXPECT_EQ(ts::read_table_cache(ea)->model, "model A");
  EXPECT_EQ(entry(a, "elsewhere/model.obj", o).key, ea.key) << "keyed by content, not by path";

  fs::copy_file(ea.file, eb.file, fs::copy_options::overwrite_existing);
  std::optional<ts::QualityTable> got;
  const std::string err = note_of([&] { got = ts::read_table_cache(eb); });
  EXPECT_FALSE(got) << "model A's table served for model B";
  EXPECT_NE(err.find("other inputs"), std::string::npos) << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;

  // Other options, same file name: a wrong key is a miss.
  ts::TableOptions finer = o;
  finer.angle_step_deg = o.angle_step_deg / 2;
  ts::TableCacheEntry wrong = entry(a, "one/model.obj", finer);
  EXPECT_NE(wrong.key, ea.key);
  wrong.file = ea.file;
  EXPECT_NE(note_of([&] { got = ts::read_table_cache(wrong); }).find("other inputs"),
            std::string::npos);
  EXPECT_FALSE(got);
}

TEST_F(TableCaching, AFlippedByteOrATruncationIsAMiss) {
  const ts::TableCacheEntry e = entry(a, "model.obj", o);
  ts::write_table_cache(e, ts::table_json(ts::QualityTable{}, o));
  const auto size = fs::file_size(e.file);
  {
    std::fstream f(e.file, std::ios::in | std::ios::out | std::ios::binary);
    f.seekg(std::streamoff(size - 8));
    const char c = char(f.get());
    f.seekp(std::streamoff(size - 8));
    f.put(char(c ^ 1));
  }
  std::optional<ts::QualityTable> got;
  EXPECT_NE(note_of([&] { got = ts::read_table_cache(e); }).find("checksum"), std::string::npos);
  EXPECT_FALSE(got);
  fs::resize_file(e.file, size / 2);
  EXPECT_NE(note_of([&] { got = ts::read_table_cache(e); }).find("truncated"), std::string::npos);
  EXPECT_FALSE(got);
  // A directory where the entry belongs: a miss, and writing fails with a warning.
  fs::remove(e.file);
  fs::create_directories(e.file);
  EXPECT_NE(note_of([&] { got = ts::read_table_cache(e); }).find("not a regular file"),
            std::string::npos);
  EXPECT_FALSE(got);
  EXPECT_NE(note_of([&] {
              ts::write_table_cache(e, ts::table_json(ts::QualityTable{}, o));
            }).find("cannot write"),
            std::string::npos);
}

}  // namespace
