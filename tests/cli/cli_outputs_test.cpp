// SPDX-License-Identifier: MIT
// What terrasprite promises about a user's files: it replaces only what it
// wrote (or what --overwrite names), checks every output before the work,
// and an interrupted run leaves nothing of its own behind.
#include <fmt/format.h>
#include <gdal.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "test_util.h"

namespace fs = std::filesystem;

namespace {

// A small, fast render; `extra` adds or overrides options.
const std::string kRender =
    "render --synthetic-size 33 --mode lod --lod-quads 4 --frames 1 --size 16x16 ";

// Runs the CLI with `dir` as the working directory.
tstest::CliResult run_in(const fs::path& dir, const std::string& args) {
  return tstest::run_cli_in(dir.string(), args);
}

void expect_refused(const tstest::CliResult& r, const std::string& args,
                    const std::string& fragment) {
  EXPECT_EQ(r.status, 2) << args << "\n" << r.output;
  EXPECT_NE(r.output.find(fragment), std::string::npos) << args << "\n" << r.output;
  EXPECT_LE(std::count(r.output.begin(), r.output.end(), '\n'), 1) << args << "\n" << r.output;
}

std::string read(const fs::path& p) {
  std::ifstream in(p);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

// A folder of the user's with two files in it.
fs::path user_folder(const fs::path& at) {
  fs::create_directories(at / "deep");
  std::ofstream(at / "precious.txt") << "mine";
  std::ofstream(at / "deep" / "thesis.tex") << "also mine";
  return at;
}

void expect_intact(const fs::path& folder) {
  EXPECT_EQ(read(folder / "precious.txt"), "mine") << folder;
  EXPECT_EQ(read(folder / "deep" / "thesis.tex"), "also mine") << folder;
}

}  // namespace

TEST(CliOutputs, RefusesTheWorkingDirectoryAndItsAncestors) {
  tstest::TempDir tmp;
  const fs::path work = user_folder(tmp.path / "work");
  user_folder(work / "sub" / "inner");
  for (const std::string& out :
       std::vector<std::string>{".", "./", "..", "sub/inner/..", "sub/inner/../..", "/",
                                work.string(), tmp.path.string()}) {
    const std::string args = kRender + "--out " + out;
    expect_refused(run_in(work, args), args, out == "/" ? "root" : out);
    expect_intact(work);
    expect_intact(work / "sub" / "inner");
  }
  // Even --overwrite never replaces these.
  expect_refused(run_in(work, kRender + "--out . --overwrite"), "--out . --overwrite", ".");
  expect_intact(work);
}

TEST(CliOutputs, RefusesFilesDevicesLinksAndForeignFolders) {
  tstest::TempDir tmp;
  std::ofstream(tmp / "afile") << "not a folder";
  const fs::path mydata = user_folder(tmp.path / "mydata");
  fs::create_directory_symlink(mydata, tmp.path / "link");
  for (const std::string& out : {tmp / "afile", std::string("/dev/null"), tmp / "link"}) {
    const std::string args = kRender + "--out " + out;
    expect_refused(tstest::run_cli(args), args, out);
    expect_refused(tstest::run_cli(args + " --overwrite"), args + " --overwrite", out);
  }
  EXPECT_EQ(read(tmp.path / "afile"), "not a folder");
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
  const std::string args = kRender + "--out " + mydata.string();
  expect_refused(tstest::run_cli(args), args, "not a terrasprite output");
  expect_intact(mydata);
  EXPECT_FALSE(fs::exists(tmp / "mydata.partial"));
  // The user says so: replaced.
  tstest::CliResult r = tstest::run_cli(args + " --overwrite");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_FALSE(fs::exists(mydata / "precious.txt"));
  EXPECT_TRUE(fs::exists(mydata / "frame_0000.png"));
}

TEST(CliOutputs, ReplacesItsOwnOutputsAndEmptyFolders) {
  tstest::TempDir tmp;
  fs::create_directory(tmp.path / "empty");
  for (int run = 0; run < 2; ++run) {
    tstest::CliResult r =
        tstest::run_cli(kRender + "--out " + (tmp / "empty") + " --json " + (tmp / "s.json"));
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_TRUE(fs::exists(tmp.path / "empty" / ".terrasprite-output"));
    EXPECT_NE(read(tmp.path / "s.json").find("\"generator\": \"terrasprite "), std::string::npos);
  }
  EXPECT_FALSE(fs::exists(tmp / "empty.partial"));
  for (const auto& e : fs::directory_iterator(tmp.path))  // nothing left aside
    EXPECT_EQ(e.path().filename().string().find(".replaced"), std::string::npos) << e.path();
}

TEST(CliOutputs, SingleFileOutputsAreCheckedBeforeTheWork) {
  tstest::TempDir tmp;
  fs::create_directory(tmp.path / "adir");
  std::ofstream(tmp / "theirs.json") << "{\"mine\": true}\n";
  const std::string out = " --out " + (tmp / "r");
  for (const std::string& json :
       {tmp / "adir", std::string("/proc/x/y.json"), tmp / "no/such/dir/s.json",
        std::string("/dev/null"), tmp / "theirs.json"}) {
    const std::string args = kRender + "--json " + json + out;
    expect_refused(tstest::run_cli(args), args, json);
    EXPECT_FALSE(fs::exists(tmp / "r")) << args;
    EXPECT_FALSE(fs::exists(tmp / "r.partial")) << args;
  }
  EXPECT_EQ(read(tmp.path / "theirs.json"), "{\"mine\": true}\n");
  expect_refused(tstest::run_cli("info --synthetic-size 33 --json " + (tmp / "theirs.json")),
                 "info --json theirs.json", "theirs.json");
  ASSERT_EQ(tstest::run_cli("info --synthetic-size 33 --overwrite --json " + (tmp / "theirs.json"))
                .status,
            0);
  EXPECT_NE(read(tmp.path / "theirs.json").find("\"generator\""), std::string::npos);
  // No temporary file left beside the target.
  for (const auto& e : fs::directory_iterator(tmp.path))
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
}

TEST(CliOutputs, NeverRemovesAPartialItDidNotCreate) {
  tstest::TempDir tmp;
  const fs::path partial = user_folder(tmp.path / "r.partial");
  const std::string args = kRender + "--out " + (tmp / "r");
  expect_refused(tstest::run_cli(args), args, "r.partial already exists");
  expect_refused(tstest::run_cli(args + " --overwrite"), args + " --overwrite", "r.partial");
  expect_intact(partial);
  EXPECT_FALSE(fs::exists(tmp / "r"));
}

TEST(CliOutputs, AnInterruptRemovesOnlyThisRunsPartial) {
  tstest::TempDir tmp;
  for (const auto& [sig, status] :
       {std::pair{"INT", 130}, std::pair{"TERM", 143}, std::pair{"HUP", 129}}) {
    const std::string out = tmp / (std::string("r") + sig);
    // Start a long render, wait for its partial directory, then signal it.
    const std::string script = fmt::format(
        "{} render --synthetic-size 65 --mode lod --frames 100000 --size 32x32 --out {} & pid=$!; "
        "for i in $(seq 600); do [ -f {}.partial/frame_0002.png ] && break; sleep 0.05; done; "
        "kill -{} $pid; wait $pid; echo status=$?",
        TS_CLI, out, out, sig);
    tstest::CliResult r = tstest::run_shell(script);
    EXPECT_NE(r.output.find(fmt::format("status={}", status)), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("interrupted by SIG"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("removed partial output " + out + ".partial"), std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists(out + ".partial"));
    EXPECT_FALSE(fs::exists(out));
  }
}

namespace {

// A PNG of the user's (written by GDAL, not terrasprite).
void users_png(const fs::path& p) {
  GDALAllRegister();
  GDALDatasetH mem = GDALCreate(GDALGetDriverByName("MEM"), "", 8, 8, 3, GDT_Byte, nullptr);
  GDALClose(
      GDALCreateCopy(GDALGetDriverByName("PNG"), p.c_str(), mem, FALSE, nullptr, nullptr, nullptr));
  GDALClose(mem);
  fs::remove(p.string() + ".aux.xml");
}

}  // namespace

TEST(CliOutputs, RerunsReplaceTheirOwnImagesNeverTheUsers) {
  tstest::TempDir tmp;
  ASSERT_EQ(tstest::run_cli(kRender + "--out " + (tmp / "r")).status, 0);
  const std::string frame = tmp / "r/frame_0000.png";
  const std::string compare = "compare " + frame + " " + frame + " --diff ";
  for (int run = 0; run < 2; ++run) {
    const tstest::CliResult r = tstest::run_cli(compare + (tmp / "d.png"));
    EXPECT_EQ(r.status, 0) << "run " << run << ": " << r.output;
  }
  users_png(tmp.path / "mine.png");
  const std::string before = read(tmp.path / "mine.png");
  expect_refused(tstest::run_cli(compare + (tmp / "mine.png")), "compare --diff mine.png",
                 "mine.png: exists and was not written by terrasprite");
  EXPECT_EQ(read(tmp.path / "mine.png"), before);
}

TEST(CliOutputs, RerunsReplaceTheirOwnVideosAndNeverTouchTheUsersPartial) {
  if (!tstest::have_tool("ffmpeg")) GTEST_SKIP() << "no ffmpeg";
  tstest::TempDir tmp;
  std::ofstream(tmp / "v.mp4.partial") << "the user's";
  const std::string render =
      "render --synthetic-size 33 --mode lod --lod-quads 4 --frames 2 --size 16x16 --video ";
  const std::string video = render + (tmp / "v.mp4");
  for (int run = 0; run < 2; ++run) {
    const tstest::CliResult r = tstest::run_cli(video);
    EXPECT_EQ(r.status, 0) << "run " << run << ": " << r.output;
  }
  EXPECT_EQ(read(tmp.path / "v.mp4.partial"), "the user's");
  // A failing encoder leaves the user's .partial too.
  const tstest::CliResult bad =
      tstest::run_cli_prefixed("env TERRASPRITE_FFMPEG=/bin/false", video + " --overwrite");
  EXPECT_EQ(bad.status, 2) << bad.output;
  EXPECT_EQ(read(tmp.path / "v.mp4.partial"), "the user's");
  // Another program's MP4 is the user's.
  ASSERT_EQ(tstest::run_shell("ffmpeg -v error -f lavfi -i color=c=red:s=32x32:d=0.2 -y " +
                              (tmp / "theirs.mp4"))
                .status,
            0);
  expect_refused(tstest::run_cli(render + (tmp / "theirs.mp4")), "--video theirs.mp4",
                 "theirs.mp4: exists and was not written by terrasprite");
  expect_refused(tstest::run_cli(render + tmp.path.string()), "--video DIR",
                 "is a directory, not an output file");
  for (const auto& e : fs::directory_iterator(tmp.path))
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
}

TEST(CliOutputs, AnInterruptedVideoLeavesNeitherItsStreamNorFfmpegsLog) {
  if (!tstest::have_tool("ffmpeg")) GTEST_SKIP() << "no ffmpeg";
  tstest::TempDir tmp;
  fs::create_directory(tmp.path / "tmp");
  const std::string script = fmt::format(
      "TMPDIR={} {} render --synthetic-size 65 --mode lod --frames 100000 --size 32x32 --video "
      "{} & pid=$!; for i in $(seq 600); do ls -A {} | grep -q tmp- && break; sleep 0.05; done; "
      "sleep 0.3; kill -HUP $pid; wait $pid; echo status=$?",
      tmp / "tmp", TS_CLI, tmp / "v.mp4", tmp.path.string());
  const tstest::CliResult r = tstest::run_shell(script);
  EXPECT_NE(r.output.find("status=129"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("interrupted by SIGHUP"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::is_empty(tmp.path / "tmp")) << "ffmpeg's log was left";
  fs::remove(tmp.path / "tmp");
  for (const auto& e : fs::directory_iterator(tmp.path)) ADD_FAILURE() << "left " << e.path();
}

TEST(CliOutputs, AFileSizeLimitFailsTheRunAndLeavesNothingComplete) {
  tstest::TempDir tmp;
  // 16 KB a file: the PNG frames of 256 x 256 do not fit.
  const std::string limited = "ulimit -f 16; ";
  tstest::CliResult r = tstest::run_shell(
      limited + TS_CLI + " render --synthetic-size 65 --frames 2 --size 256x256 --out " +
      (tmp / "o"));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("cannot write PNG (File too large)"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(tmp / "o"));
  EXPECT_FALSE(fs::exists(tmp / "o.partial"));
  if (tstest::have_tool("ffmpeg")) {
    r = tstest::run_shell(
        limited + TS_CLI +
        " render --synthetic-size 65 --frames 40 --size 256x256 --crf 0 --video " +
        (tmp / "v.mp4"));
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_NE(r.output.find("v.mp4: video encoding failed"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(tmp / "v.mp4"));
  }
  for (const auto& e : fs::directory_iterator(tmp.path)) ADD_FAILURE() << "left " << e.path();
}
