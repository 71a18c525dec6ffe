// SPDX-License-Identifier: MIT
// The viewer: script parsing, flight controls, stats, and scripted runs of the
// real window under Xvfb (skipped when xvfb-run is missing).
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "flat_field.h"
#include "terrasprite/common/error.h"
#include "terrasprite/terrain/terrain.h"
#include "test_util.h"
#include "viewer/fly_controller.h"
#include "viewer/input_event.h"
#include "viewer/path_recorder.h"
#include "viewer/run_stats.h"

namespace fs = std::filesystem;
using namespace terrasprite;
using namespace terrasprite::viewer;

namespace {

Heightfield flat(int n, double spacing, float z) {
  return viewer_test::flat_field(n, spacing, z);
}

InputEvent key(int k, int action) {
  InputEvent e;
  e.kind = InputKind::kKey;
  e.key = k;
  e.action = action;
  return e;
}

nlohmann::json read_json(const std::string& f) {
  return nlohmann::json::parse(std::ifstream(f));
}

bool have_xvfb() {
  return tstest::have_tool("xvfb-run");
}

/// `view` under Xvfb on a small synthetic terrain.
tstest::CliResult view(const std::string& args) {
  return tstest::run_cli_prefixed("xvfb-run -a", "view --synthetic-size 129 --size 160x90 " + args);
}

}  // namespace

TEST(InputScript, ParsesSortsAndNamesKeys) {
  tstest::TempDir tmp;
  std::ofstream(tmp / "s.json") << R"({"events": [
    {"t": 2.0, "type": "key", "key": "W", "action": "release"},
    {"t": 0.5, "type": "key", "key": "W", "action": "press"},
    {"t": 2.5, "type": "mouse", "dx": 40, "dy": 0},
    {"t": 2.6, "type": "button", "button": "left", "action": "press"},
    {"t": 2.7, "type": "wheel", "dy": 1},
    {"t": 3.0, "type": "screenshot", "file": "a.png"}]})";
  auto s = load_input_script(tmp / "s.json");
  ASSERT_EQ(s.size(), 6u);
  EXPECT_EQ(s[0].t, 0.5);
  EXPECT_EQ(s[0].event.key, GLFW_KEY_W);
  EXPECT_EQ(s[0].event.action, GLFW_PRESS);
  EXPECT_EQ(s[2].event.dx, 40);
  EXPECT_EQ(s[3].event.button, GLFW_MOUSE_BUTTON_LEFT);
  EXPECT_EQ(s[5].event.file, "a.png");
  EXPECT_EQ(key_code("F12"), GLFW_KEY_F12);
  EXPECT_EQ(key_code("ESCAPE"), GLFW_KEY_ESCAPE);
  EXPECT_EQ(key_code("7"), GLFW_KEY_7);
  EXPECT_EQ(key_code("F13"), -1);
  EXPECT_EQ(key_code("w"), -1);
}

TEST(InputScript, BadFilesAreOneLineInputErrors) {
  tstest::TempDir tmp;
  const std::pair<const char*, const char*> cases[] = {
      {"not json", "not a JSON object"},
      {R"({"events": 3})", "\"events\" must be an array"},
      {R"({"events": [{"t": 1, "type": "key", "key": "WW", "action": "press"}]})", "unknown key"},
      {R"({"events": [{"t": 1, "type": "key", "key": "W", "action": "hold"}]})", "\"action\""},
      {R"({"events": [{"t": -1, "type": "wheel", "dy": 1}]})", "\"t\""},
      {R"({"events": [{"t": 1, "type": "teleport"}]})", "\"type\""},
      {R"({"events": [{"t": 1, "type": "mouse", "dx": "far"}]})", "\"dx\""},
      {R"({"events": [{"t": 1, "type": "key", "key": "W", "action": 2.7}]})", "\"action\""},
      {R"({"events": [{"t": 1, "type": "button", "button": 1, "action": "press"}]})",
       "unknown button"}};
  int i = 0;
  for (const auto& [text, fragment] : cases) {
    const std::string f = tmp / ("bad" + std::to_string(i++) + ".json");
    std::ofstream(f) << text;
    try {
      load_input_script(f);
      ADD_FAILURE() << text;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(f), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(load_input_script(tmp / "missing.json"), InputError);
}

// Numbers past their bounds are refused, naming FILE:LINE and the event.
TEST(InputScript, OutOfRangeNumbersNameTheFileLineAndEvent) {
  tstest::TempDir tmp;
  const std::pair<const char*, const char*> cases[] = {
      {"{\"events\": [\n  {\"type\": \"wheel\", \"dy\": 1},\n  {\"type\": \"wheel\", \"dy\": "
       "1e308}]}",
       ":3: event 1: \"dy\" 1e+308 must be between -100 and 100"},
      {"{\"events\": [{\"type\": \"mouse\",\n \"dx\": 1}, {\"type\": \"mouse\", \"dx\": -1e6}]}",
       ":2: event 1: \"dx\" -1e+06 must be between -100000 and 100000"},
      {"{\"note\": \"[events\\\"]\",\n\"events\":\n[\n\n{\"t\": 1e300, \"type\": \"wheel\"}]}",
       ":5: event 0: \"t\" 1e+300 must be between 0 and 86400"},
      {"{\"events\": [], \"events\": [{\"type\": \"wheel\"},\n{\"type\": \"wheel\", \"dx\": "
       "-101}]}",
       ":2: event 1: \"dx\" -101"}};
  int i = 0;
  for (const auto& [text, fragment] : cases) {
    const std::string f = tmp / ("range" + std::to_string(i++) + ".json");
    std::ofstream(f) << text;
    try {
      load_input_script(f);
      ADD_FAILURE() << text;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(f + fragment), std::string::npos) << e.what();
    }
  }
}

// However far the wheel turns, the speed stays within its bounds and a
// free flight stays at finite positions.
TEST(FlyController, WheelKeepsTheSpeedBounded) {
  Heightfield h = flat(65, 10, 100);
  Camera start;
  start.position = {0, 0, 150};
  FlyOptions o;
  o.bounded = false;
  FlyController fly(h, start, o);
  InputEvent wheel;
  wheel.kind = InputKind::kWheel;
  wheel.dy = 1e308;
  fly.handle(wheel);
  EXPECT_EQ(fly.speed_mps(), kMaxSpeedMps);
  fly.handle(key(GLFW_KEY_W, GLFW_PRESS));
  fly.handle(key(GLFW_KEY_Q, GLFW_PRESS));
  fly.update(1.0);
  const glm::dvec3 p = fly.camera().position;
  EXPECT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) << p.x << " " << p.y;
  EXPECT_LE(glm::length(p - start.position), 1.001 * kMaxSpeedMps * std::sqrt(2.0));
  wheel.dy = -1e308;
  fly.handle(wheel);
  EXPECT_EQ(fly.speed_mps(), kMinSpeedMps);
  wheel.dy = std::nan("");
  fly.handle(wheel);
  EXPECT_EQ(fly.speed_mps(), kMinSpeedMps);
}

TEST(FlyController, ForwardKeyMovesAlongTheHeadingAndKeepsClearance) {
  Heightfield h = flat(65, 10, 100);
  Camera start;
  start.position = {0, 0, 150};
  start.yaw_deg = 90;  // east
  start.pitch_deg = -10;
  FlyOptions o;
  o.speed_mps = 50;
  o.clearance_m = 20;
  FlyController fly(h, start, o);
  fly.handle(key(GLFW_KEY_W, GLFW_PRESS));
  fly.update(1.0);
  EXPECT_NEAR(fly.camera().position.x, 50, 1e-9);
  EXPECT_NEAR(fly.camera().position.y, 0, 1e-9);
  fly.handle(key(GLFW_KEY_W, GLFW_RELEASE));
  fly.update(1.0);
  EXPECT_NEAR(fly.camera().position.x, 50, 1e-9);
  fly.handle(key(GLFW_KEY_E, GLFW_PRESS));  // down, into the ground: stopped at the clearance
  fly.update(10.0);
  EXPECT_NEAR(fly.camera().position.z, 120, 1e-6);
  fly.handle(key(GLFW_KEY_E, GLFW_RELEASE));
  InputEvent look;
  look.kind = InputKind::kMouse;
  look.dx = 100;  // 15 degrees right at 0.15 deg/px
  fly.handle(look);
  EXPECT_NEAR(fly.camera().yaw_deg, 105, 1e-9);
  fly.handle(key(GLFW_KEY_R, GLFW_PRESS));
  EXPECT_NEAR(fly.camera().position.x, 0, 1e-9);
}

TEST(FlyController, StaysNearTheTerrainAndOrbitsAPickedPoint) {
  Heightfield h = flat(65, 10, 0);  // 640 m square
  Camera start;
  start.position = {0, -200, 100};
  start.yaw_deg = 0;
  start.pitch_deg = -26.565;  // looks at (0, 0, 0)
  FlyOptions o;
  o.speed_mps = 1000;
  FlyController fly(h, start, o);
  EXPECT_NEAR(fly.pick_centre().y, 0, 15);
  fly.handle(key(GLFW_KEY_W, GLFW_PRESS));
  fly.update(10);
  EXPECT_LE(fly.camera().position.y, 0.75 * 640 + 1e-9);
  fly.handle(key(GLFW_KEY_W, GLFW_RELEASE));
  fly.handle(key(GLFW_KEY_R, GLFW_PRESS));
  fly.handle(key(GLFW_KEY_O, GLFW_PRESS));
  EXPECT_TRUE(fly.orbiting());
  const double d0 = glm::length(fly.camera().position - fly.pick_centre());
  fly.handle(key(GLFW_KEY_D, GLFW_PRESS));
  fly.update(0.5);
  EXPECT_NE(fly.camera().position.x, 0.0);
  EXPECT_NEAR(glm::length(fly.camera().position - glm::dvec3(0, 0, 0)), d0, 20);
}

TEST(RunStats, KeysAndRatesFromNearestRankFrameTimes) {
  RunStats s;
  s.mode = RenderMode::kLod;
  s.frames = 3;
  s.frame_ms = {20, 40};
  s.events = {{0.5, 30}, {1.0, -1}};
  auto j = stats_json(s);
  for (const char* k : {"mode", "size", "frames", "fps_median", "fps_low_1pct", "frame_ms_p50",
                        "frame_ms_p99", "latency_ms_p95", "latency_ms_max", "events"})
    EXPECT_TRUE(j.contains(k)) << k;
  EXPECT_EQ(j["fps_median"], 50.0);
  EXPECT_EQ(j["fps_low_1pct"], 25.0);
  EXPECT_EQ(j["latency_ms_max"], 30.0);
}

TEST(PathRecorder, KeyframesEveryIntervalAndTheLastPose) {
  PathRecorder r(0.5);
  Camera c;
  for (int i = 0; i <= 10; ++i) {
    c.position.x = i;
    r.offer(i * 0.1, c);
  }
  r.close(1.05, c);
  auto j = r.json();
  ASSERT_EQ(j["keyframes"].size(), 4u);  // 0, 0.5, 1.0, 1.05
  EXPECT_EQ(j["keyframes"][1]["t"], 0.5);
  EXPECT_EQ(j["keyframes"][3]["position"][0], 10.0);
}

// A recording replaces only a file terrasprite wrote (or any, with
// overwrite): never the user's. It names its generator so a later run may
// replace it.
TEST(PathRecorder, WriteReplacesOnlyItsOwnFiles) {
  tstest::TempDir tmp;
  const std::string notes = tmp / "notes.tex", rec = tmp / "rec.json";
  std::ofstream(notes) << "my notes\n";
  PathRecorder r(0.5);
  r.close(0.0, Camera{});
  EXPECT_THROW(r.write(notes, {}), InputError);
  std::ifstream in(notes);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), "my notes\n");
  r.write(rec, {});
  EXPECT_EQ(read_json(rec)["generator"].get<std::string>().rfind("terrasprite", 0), 0u);
  r.write(rec, {});  // its own file
  r.write(notes, {.overwrite = true});
  EXPECT_EQ(read_json(notes)["keyframes"].size(), 1u);
}

TEST(ViewCli, BadScriptsExitTwoWithOneLine) {
  tstest::TempDir tmp;
  std::ofstream(tmp / "bad.json") << R"({"events": [{"t": 1, "type": "key", "key": "?"}]})";
  for (const std::string& f : {tmp / "bad.json", tmp / "missing.json"}) {
    auto r = tstest::run_cli("view --script " + f + " --stats " + (tmp / "st.json"));
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_LE(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_NE(r.output.find(f), std::string::npos) << r.output;
  }
  EXPECT_FALSE(fs::exists(tmp / "st.json"));
}

TEST(ViewCli, ScriptedRunUnderXvfbMovesRecordsAndReplays) {
  if (!have_xvfb()) GTEST_SKIP() << "xvfb-run missing";
  tstest::TempDir tmp;
  std::ofstream(tmp / "fly.json") << R"({"events": [
    {"t": 0.3, "type": "key", "key": "W", "action": "press"},
    {"t": 1.3, "type": "key", "key": "W", "action": "release"},
    {"t": 1.4, "type": "mouse", "dx": 60, "dy": 0},
    {"t": 1.5, "type": "key", "key": "F1", "action": "press"},
    {"t": 1.6, "type": "screenshot", "file": ")"
                                  << (tmp / "shot.png") << R"("}]})";
  auto r = view("--mode lod --speed 1500 --script " + (tmp / "fly.json") + " --stats " +
                (tmp / "a.json") + " --record " + (tmp / "rec.json") + " --record-every 0.25");
  ASSERT_EQ(r.status, 0) << r.output;
  auto a = read_json(tmp / "a.json");
  for (const char* k : {"mode", "size", "frames", "fps_median", "fps_low_1pct", "frame_ms_p50",
                        "frame_ms_p99", "latency_ms_p95", "latency_ms_max", "events"})
    EXPECT_TRUE(a.contains(k)) << k;
  EXPECT_EQ(a["mode"], "lod");
  EXPECT_EQ(a["size"], nlohmann::json({160, 90}));
  EXPECT_GE(a["frames"].get<int>(), 5);  // frames advance
  ASSERT_EQ(a["events"].size(), 5u);
  // Every event reaches the screen (-1: never shown), some time after it is injected.
  for (const auto& e : a["events"]) EXPECT_GT(e["latency_ms"].get<double>(), 0) << e;
  EXPECT_TRUE(fs::exists(tmp / "shot.png"));
  // W flies along the start heading, on the level.
  const auto& p0 = a["camera_start"]["position"];
  const auto& p1 = a["camera_end"]["position"];
  const double yaw = glm::radians(a["camera_start"]["yaw_deg"].get<double>());
  const double along = (p1[0].get<double>() - p0[0].get<double>()) * std::sin(yaw) +
                       (p1[1].get<double>() - p0[1].get<double>()) * std::cos(yaw);
  EXPECT_GT(along, 100.0) << a["camera_start"] << a["camera_end"];
  EXPECT_NEAR(a["camera_end"]["yaw_deg"].get<double>(),
              std::fmod(a["camera_start"]["yaw_deg"].get<double>() + 9 + 360, 360), 1e-6);
  // The recording replays to the same poses.
  auto rec = read_json(tmp / "rec.json");
  ASSERT_GE(rec["keyframes"].size(), 4u);
  const double end_t = rec["keyframes"].back()["t"].get<double>();
  std::ofstream(tmp / "wait.json") << R"({"events": [{"t": )" << end_t + 0.3
                                   << R"(, "type": "key", "key": "F1", "action": "press"}]})";
  // (replayed through the shared-context path: the window shows the renderer's texture)
  r = view("--mode lod --shared-context --play " + (tmp / "rec.json") + " --script " +
           (tmp / "wait.json") + " --stats " + (tmp / "b.json"));
  ASSERT_EQ(r.status, 0) << r.output;
  auto b = read_json(tmp / "b.json");
  EXPECT_GE(b["frames"].get<int>(), 2);
  const auto& last = rec["keyframes"].back();
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(b["camera_end"]["position"][i].get<double>(), last["position"][i].get<double>(),
                1e-3);
  EXPECT_NEAR(b["camera_end"]["yaw_deg"].get<double>(), last["yaw_deg"].get<double>(), 1e-3);
  EXPECT_NEAR(b["camera_start"]["position"][0].get<double>(),
              rec["keyframes"][0]["position"][0].get<double>(), 1e-3);
}

// A script's screenshots may repeat a file this run wrote, a recording
// replaces the one an earlier run wrote, and a wheel turned to its bound in a
// free flight moves the camera at most the speed bound. CI cost: ~5 s.
TEST(ViewCli, RepeatedOutputsAndAFarWheelUnderXvfb) {
  if (!have_xvfb()) GTEST_SKIP() << "xvfb-run missing";
  tstest::TempDir tmp;
  const std::string shot = tmp / "shot.png";
  std::ofstream(tmp / "far.json") << R"({"events": [
    {"t": 0.1, "type": "screenshot", "file": ")"
                                  << shot << R"("},
    {"t": 0.2, "type": "wheel", "dy": 100}, {"t": 0.2, "type": "wheel", "dy": 100},
    {"t": 0.2, "type": "wheel", "dy": 100},
    {"t": 0.3, "type": "key", "key": "W", "action": "press"},
    {"t": 0.8, "type": "key", "key": "W", "action": "release"},
    {"t": 0.9, "type": "screenshot", "file": ")"
                                  << shot << R"("}]})";
  auto r = view("--mode lod --free --script " + (tmp / "far.json") + " --stats " +
                (tmp / "a.json") + " --record " + (tmp / "rec.json"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(fs::exists(shot));
  const auto a = read_json(tmp / "a.json");
  const auto& p0 = a["camera_start"]["position"];
  const auto& p1 = a["camera_end"]["position"];
  const double moved = std::hypot(p1[0].get<double>() - p0[0].get<double>(),
                                  p1[1].get<double>() - p0[1].get<double>());
  EXPECT_GT(moved, 1000.0) << a;             // the wheel sped the flight up
  EXPECT_LE(moved, 10 * kMaxSpeedMps) << a;  // within the bound for the time held
  std::ofstream(tmp / "short.json")
      << R"({"events": [{"t": 0.1, "type": "key", "key": "W", "action": "press"}]})";
  r = view("--mode lod --script " + (tmp / "short.json") + " --record " + (tmp / "rec.json"));
  EXPECT_EQ(r.status, 0) << r.output;
}

// Sprite mode with its keyframes on a second thread, through the window's
// shared context (the keyframe worker takes the third hidden GLFW context):
// no frame draws a keyframe inside it, and keyframes drawn
// by the worker land while the camera flies and turns; even the first
// keyframe comes from the worker (plain LOD frames until it lands). CI cost: ~4 s.
TEST(ViewCli, SpriteKeyframesLandFromASecondThreadUnderXvfb) {
  if (!have_xvfb()) GTEST_SKIP() << "xvfb-run missing";
  tstest::TempDir tmp;
  std::ofstream(tmp / "fly.json") << R"({"events": [
    {"t": 0.2, "type": "key", "key": "W", "action": "press"},
    {"t": 1.7, "type": "key", "key": "W", "action": "release"},
    {"t": 1.8, "type": "mouse", "dx": 80, "dy": 0}]})";
  auto r = view("--mode sprite --shared-context --script " + (tmp / "fly.json") + " --stats " +
                (tmp / "s.json"));
  ASSERT_EQ(r.status, 0) << r.output;
  auto s = read_json(tmp / "s.json");
  EXPECT_EQ(s["classes"].value("key", 0), 0) << s["classes"];  // none inside a frame
  EXPECT_GE(s["classes"].value("lod", 0), 1) << s["classes"];  // until the first one lands
  EXPECT_GE(s["classes"].value("sprite", 0), 5) << s["classes"];
  EXPECT_GE(s["keyframes_landed"].get<int>(), 1) << s;
  // The worker's own time per keyframe reaches the stats (and the panel).
  EXPECT_GT(s["keyframe_ms_p50"].get<double>(), 0) << s;
  EXPECT_GE(s["keyframe_ms_max"].get<double>(), s["keyframe_ms_p50"].get<double>()) << s;
  ASSERT_EQ(s["events"].size(), 3u);
  for (const auto& e : s["events"]) EXPECT_GT(e["latency_ms"].get<double>(), 0) << e;
}

// Voxel mode with the warp (every third frame real) and the panel's compare
// (F3): warped frames are displayed, and the comparison with full resolution
// is in the stats. CI cost: ~5 s.
TEST(ViewCli, VoxelWithWarpAndCompareUnderXvfb) {
  if (!have_xvfb()) GTEST_SKIP() << "xvfb-run missing";
  tstest::TempDir tmp;
  std::ofstream(tmp / "cmp.json") << R"({"events": [
    {"t": 0.2, "type": "key", "key": "W", "action": "press"},
    {"t": 1.2, "type": "key", "key": "W", "action": "release"},
    {"t": 1.3, "type": "key", "key": "F3", "action": "press"},
    {"t": 1.4, "type": "key", "key": "F3", "action": "release"},
    {"t": 2.5, "type": "key", "key": "F4", "action": "press"}]})";
  auto r = view("--mode voxel --warp poly2 --real-every 3 --voxel-ratio 2 --script " +
                (tmp / "cmp.json") + " --stats " + (tmp / "s.json"));
  ASSERT_EQ(r.status, 0) << r.output;
  auto s = read_json(tmp / "s.json");
  EXPECT_GE(s["classes"].value("voxel", 0), 1) << s["classes"];
  EXPECT_GE(s["classes"].value("warp", 0), 2) << s["classes"];
  ASSERT_EQ(s["comparisons"].size(), 1u) << s["comparisons"];
  const auto& c = s["comparisons"][0];
  EXPECT_EQ(c["mode"], "voxel");
  // The voxel caster and the GL mesh agree broadly, and not exactly.
  EXPECT_GT(c["ssim"].get<double>(), 0.3) << c;
  EXPECT_LT(c["ssim"].get<double>(), 1.0) << c;
  EXPECT_GT(c["psnr"].get<double>(), 12.0) << c;
  EXPECT_GT(c["flip"].get<double>(), 0.0) << c;
  EXPECT_LT(c["flip"].get<double>(), 1.0) << c;
  // Bad values are one line and exit 2.
  for (const char* bad : {"--voxel-ratio 0", "--real-every 0", "--warp sideways"}) {
    auto b = view(std::string("--mode voxel --frames 1 ") + bad);
    EXPECT_EQ(b.status, 2) << bad << ": " << b.output;
  }
}
