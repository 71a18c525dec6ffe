// SPDX-License-Identifier: MIT
// Hostile scene files, viewer scripts and viewer options, each run in a
// working directory holding the user's files: one line naming the input and
// the field, exit status 2, nothing written and nothing removed. Scene files
// are refused the same way by `objects scene --scene` and `render --objects`
// (one parser). Every view row fails before its window opens. CI cost: ~6 s
// (the render rows start a GL context before they read the scene).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>

#include "hostile_row.h"
#include "test_util.h"

namespace fs = std::filesystem;

namespace {

struct SceneRow {
  const char* file;      ///< a scene file of make_scenes()
  const char* fragment;  ///< the one line must contain this
};

const SceneRow kScenes[] = {
    {"scale.json", "scale.json: instances[0].scale 1e+30: must be in [0.001, 1000]"},
    {"far.json", "far.json: instances[1].position [1e+308, -1e+308]: x and y must be within"},
    {"high.json", "high.json: instances[0].position z 1e+308: must be within"},
    {"count32.json",
     "count32.json: scatter[0].count 4294967297: must be a whole number in 0..1000000"},
    {"count1e10.json", "count1e10.json: scatter[0].count 10000000000: must be a whole number"},
    {"upx.json", "upx.json: models[1].up (model c): 'x' is not an up axis (y or z)"},
    {"slope.json", "slope.json: scatter[0].max_slope_deg 1e+308: must be in [0, 90]"},
};

struct Row {
  const char* args;
  const char* fragment;
};

#define VIEW "view --synthetic-size 33 --size 64x64 "

const Row kViewRows[] = {
    {VIEW "--clearance 1e308", "--clearance 1e+308: must be in [0, 100000]"},
    {VIEW "--clearance -1", "--clearance -1"},
    {VIEW "--speed 1e308", "--speed 1e+308: must be in [0, 1e+06]"},
    {VIEW "--record-every 1e308", "--record-every 1e+308"},
    {VIEW "--record notes.tex", "notes.tex: exists and was not written by terrasprite"},
    {VIEW "--record adir", "adir: is a directory"},
    {VIEW "--script shot.json", "thesis.tex: exists and was not written by terrasprite"},
    {VIEW "--script shotdir.json", "adir: is a directory"},
    {VIEW "--script wheel.json",
     "wheel.json:3: event 1: \"dy\" 1e+308 must be between -100 and 100"},
    {VIEW "--script mouse.json", "mouse.json:2: event 0: \"dx\" -1e+308 must be between"},
    {VIEW "--script late.json", "late.json:1: event 0: \"t\" 1e+300 must be between 0 and 86400"},
    {VIEW "--screenshot-dir afile", "--screenshot-dir afile: not a directory"},
    {VIEW "--stats thesis.tex", "thesis.tex: exists and was not written by terrasprite"},
};

void write_file(const fs::path& p, const std::string& text) {
  std::ofstream(p) << text;
}

// The user's files and every hostile input.
void make_fixtures(const fs::path& w) {
  write_file(w / "thesis.tex", "\\documentclass{article}\n");
  write_file(w / "notes.tex", "my notes\n");
  write_file(w / "afile", "a file of mine");
  fs::create_directory(w / "adir");
  const std::string m = R"({"models": [{"name": "b", "file": "b.obj"}], )";
  write_file(w / "scale.json",
             m + R"("instances": [{"model": "b", "position": [0, 0], "scale": 1e30}]})");
  write_file(w / "far.json", m + R"("instances": [{"model": "b", "position": [0, 0]},
                                                  {"model": "b", "position": [1e308, -1e308]}]})");
  write_file(w / "high.json", m + R"("instances": [{"model": "b", "position": [0, 0, 1e308]}]})");
  write_file(w / "count32.json", m + R"("scatter": [{"model": "b", "count": 4294967297}]})");
  write_file(w / "count1e10.json", m + R"("scatter": [{"model": "b", "count": 1e10}]})");
  write_file(w / "upx.json", R"({"models": [{"name": "b", "file": "b.obj"},
                                            {"name": "c", "file": "c.obj", "up": "x"}]})");
  write_file(w / "slope.json",
             m + R"("scatter": [{"model": "b", "count": 3, "max_slope_deg": 1e308}]})");
  write_file(w / "shot.json",
             R"({"events": [{"t": 0.1, "type": "screenshot", "file": "thesis.tex"}]})");
  write_file(w / "shotdir.json",
             R"({"events": [{"t": 0.1, "type": "screenshot", "file": "adir"}]})");
  write_file(w / "wheel.json",
             "{\"events\": [\n  {\"t\": 0.1, \"type\": \"wheel\", \"dy\": 1},\n"
             "  {\"t\": 0.2, \"type\": \"wheel\", \"dy\": 1e308}\n]}\n");
  write_file(w / "mouse.json", "{\"events\": [\n{\"type\": \"mouse\", \"dx\": -1e308}]}\n");
  write_file(w / "late.json",
             R"({"events": [{"t": 1e300, "type": "key", "key": "W", "action": "press"}]})");
}

using tstest::snapshot;

using tstest::expect_refused_untouched;

}  // namespace

TEST(HostileScenes, ObjectsSceneAndRenderObjectsRefuseTheSameFiles) {
  tstest::TempDir tmp;
  const fs::path work = tmp.path / "work";
  fs::create_directory(work);
  make_fixtures(work);
  const auto before = snapshot(work);
  for (const SceneRow& row : kScenes) {
    expect_refused_untouched(
        work,
        std::string("objects scene --synthetic-size 33 --size 16x16 --frames 1 "
                    "--cache off --out o --scene ") +
            row.file,
        row.fragment, before);
    expect_refused_untouched(
        work,
        std::string("render --synthetic-size 33 --size 16x16 --frames 1 --mode full "
                    "--objects-cache off --out o --objects ") +
            row.file,
        row.fragment, before);
  }
}

TEST(HostileScenes, ViewRefusesBadNumbersScriptsAndTheUsersFiles) {
  tstest::TempDir tmp;
  const fs::path work = tmp.path / "work";
  fs::create_directory(work);
  make_fixtures(work);
  const auto before = snapshot(work);
  for (const Row& row : kViewRows) expect_refused_untouched(work, row.args, row.fragment, before);
}
