// SPDX-License-Identifier: MIT
// Hostile model files and model options on the command line, each run in a
// working directory of the user's files: one line naming the input, exit
// status 2, nothing written; a missing material library is one warning.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "hostile_row.h"
#include "test_util.h"

namespace fs = std::filesystem;

namespace {

struct ModelRow {
  const char* args;      ///< CLI arguments, run in the work directory
  const char* fragment;  ///< the one line must contain this
};

const ModelRow kModelRows[] = {
    {"objects info --model t.obj --height-m 1e308", "--height-m: height 1e+308 m is not in"},
    {"objects info --model t.obj --height-m inf", "--height-m: inf is not a finite number"},
    {"objects info --model t.obj --height-m nan", "--height-m: nan is not a finite number"},
    {"objects info --model t.obj --height-m -1", "--height-m"},
    {"objects info --model adir.obj", "adir.obj: is a directory"},
    {"objects info --model nosuch.obj", "nosuch.obj: no such model file"},
    {"objects info --model indented.obj", "indented.obj: line 2: coordinate 'nan'"},
    {"objects info --model wide.obj", "wide.obj: the model spans"},
    {"objects info --model cut.obj", "cut.obj: line 5: a face has 2 corners"},
    {"objects info --model noend.obj", "noend.obj: line 5: the last line has no end"},
};

void write_file(const fs::path& p, const std::string& text) {
  std::ofstream(p, std::ios::binary) << text;
}

void make_model_fixtures(const fs::path& w) {
  const std::string verts = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n";
  write_file(w / "t.obj", verts + "f 1 2 3\n");
  fs::create_directory(w / "adir.obj");
  write_file(w / "indented.obj", "v 0 0 0\n   v nan nan nan\nv 0 1 0\nf 1 2 3\n");
  write_file(w / "wide.obj", "v -3e38 0 0\nv 3e38 0 0\nv 0 1 0\nf 1 2 3\n");
  write_file(w / "cut.obj", verts + "f 1 2\n");
  write_file(w / "noend.obj", verts + "f 1 2 3");
  write_file(w / "mtl.obj", "mtllib nowhere.mtl\nusemtl m\n" + verts + "f 1 2 3\n");
}

}  // namespace

// About 0.1 s per row.
TEST(HostileModels, EachFailsInOneLineAndWritesNothing) {
  tstest::TempDir tmp;
  const fs::path work = tmp.path / "work";
  fs::create_directory(work);
  make_model_fixtures(work);
  const auto before = tstest::snapshot(work);
  for (const ModelRow& row : kModelRows) {
    const tstest::CliResult r =
        tstest::expect_refused_untouched(work, row.args, row.fragment, before);
    EXPECT_LT(r.output.size(), 300u) << row.args;
  }
}

// 0.1 s.
TEST(HostileModels, MissingMaterialLibraryIsOneWarning) {
  tstest::TempDir tmp;
  make_model_fixtures(tmp.path);
  const tstest::CliResult r = tstest::run_shell("cd '" + tmp.path.string() + "' && " + TS_CLI +
                                                " objects info --model mtl.obj 2>&1 >/dev/null");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_NE(r.output.find("warning: mtl.obj: material library nowhere.mtl not found"),
            std::string::npos)
      << r.output;
}
