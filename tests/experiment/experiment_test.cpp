// SPDX-License-Identifier: MIT
// The experiment driver with fake renderers (no GL): what it draws, reads
// back, scores and keeps, frame by frame. CI cost: well under a second.
#include "terrasprite/experiment/experiment.h"

#include <gtest/gtest.h>

#include <map>
#include <set>
#include <string>
#include <vector>

#include "terrasprite/experiment/flythrough.h"

namespace terrasprite {
namespace {

// Draws a flat grey image whose value is the camera's x position; records
// every call so the test can see the driver's order.
class FakeRenderer final : public Renderer {
 public:
  FakeRenderer(std::string name, int offset, std::vector<std::string>& log)
      : name_(std::move(name)), offset_(offset), log_(log) {}
  Frame draw(const Camera& c) override {
    log_.push_back(name_ + " draw");
    last_ = int(c.position.x) + offset_;
    Frame f;
    f.cls = last_ % 2 ? FrameClass::kKey : FrameClass::kSprite;
    f.ms = double(last_);
    f.width_px = 4;
    f.height_px = 4;
    f.camera = c;
    return f;
  }
  void read_back(Frame& f, ReadBack what) override {
    log_.push_back(name_ + " read");
    if (has(what, ReadBack::kColor)) {
      f.color = Image(4, 4);
      for (std::size_t i = 0; i < f.color.rgba.size(); ++i)
        f.color.rgba[i] = i % 4 == 3 ? 255 : std::uint8_t(last_);
    }
  }
  std::string name() const override { return name_; }

 private:
  std::string name_;
  int offset_;
  int last_ = 0;
  std::vector<std::string>& log_;
};

std::vector<Camera> path_of(int n) {
  std::vector<Camera> p(n);
  for (int i = 0; i < n; ++i) p[i].position.x = 10.0 * i;
  return p;
}

// Scores by the difference of the images' first byte, so a test can tell
// which frames were compared.
QualityScore byte_scorer(const Frame& ref, const Frame& test) {
  QualityScore q;
  q.psnr = double(test.color.rgba[0]) - double(ref.color.rgba[0]);
  q.ssim = 1.0;
  q.flip = 0.0;
  return q;
}

TEST(Experiment, DrawsReadsAndScoresInOrderAgainstTheReference) {
  std::vector<std::string> log;
  FakeRenderer ref("ref", 0, log), a("a", 1, log), b("b", 2, log);
  Experiment e;
  e.set_reference(ref, "ref");
  e.add({.renderer = &a, .name = "a", .score = true});
  e.add({.renderer = &b, .name = "b", .every = 2});  // not scored, every other frame
  ExperimentOptions o;
  o.warmup_draws = 1;
  o.scorer = byte_scorer;
  o.score_every = 2;
  PathSource cams(path_of(4));
  const ExperimentResult r = e.run(cams, o);
  ASSERT_EQ(r.frames, 4);
  ASSERT_EQ(r.runs.size(), 3u);
  EXPECT_EQ(r.runs[0].name, "ref");
  EXPECT_EQ(r.runs[0].frames.size(), 2u) << "the reference draws on scored frames only";
  EXPECT_EQ(r.runs[1].frames.size(), 4u);
  EXPECT_EQ(r.runs[2].frames.size(), 2u) << "every = 2";
  // Frame 0: warm-ups first (one draw each, no read), then ref, a, b; frame 1: only a.
  const std::vector<std::string> head = {"ref draw", "a draw", "b draw", "ref draw", "ref read",
                                         "a draw",   "a read", "b draw", "a draw"};
  ASSERT_GE(log.size(), head.size());
  EXPECT_EQ(std::vector<std::string>(log.begin(), log.begin() + head.size()), head);
  // a is scored on frames 0 and 2 against that frame's reference: 1 apart.
  const RendererRun& ra = r.run("a");
  ASSERT_TRUE(ra.frames[0].quality);
  EXPECT_EQ(ra.frames[0].quality->psnr, 1.0);
  EXPECT_FALSE(ra.frames[1].quality);
  ASSERT_TRUE(ra.frames[2].quality);
  EXPECT_EQ(ra.frames[2].quality->psnr, 1.0);
  EXPECT_FALSE(r.run("b").frames[0].quality) << "b does not ask to be scored";
  // Times and classes come from the frames: a draws 1, 11, 21, 31.
  EXPECT_EQ(ra.ms().median, 16.0) << "median of 1, 11, 21, 31";
  EXPECT_EQ(ra.ms().p90, 31.0) << "nearest rank: the 4th of 4";
  EXPECT_EQ(ra.count(FrameClass::kKey), 4);             // the odd frames
  EXPECT_EQ(r.run("b").count(FrameClass::kSprite), 2);  // the even frames
  EXPECT_THROW(r.run("nobody"), std::out_of_range);
}

TEST(Experiment, StreamsResultsWithoutKeepingThem) {
  std::vector<std::string> log;
  FakeRenderer a("a", 0, log);
  Experiment e;
  e.add({.renderer = &a, .name = "a"});
  std::vector<double> seen;
  ExperimentOptions o;
  o.warmup_draws = 0;
  o.keep_frames = false;
  o.on_result = [&](const std::string& name, const FrameResult& f) {
    EXPECT_EQ(name, "a");
    seen.push_back(f.ms);
  };
  PathSource cams(path_of(5));
  const ExperimentResult r = e.run(cams, o);
  EXPECT_EQ(r.frames, 5);
  EXPECT_TRUE(r.run("a").frames.empty());
  EXPECT_EQ(seen, (std::vector<double>{0, 10, 20, 30, 40}));
}

TEST(Experiment, AParticipantCanFlyItsOwnCameras) {
  std::vector<std::string> log;
  FakeRenderer a("a", 0, log), b("b", 0, log);
  Experiment e;
  e.add({.renderer = &a, .name = "a"});
  e.add({.renderer = &b, .name = "b", .camera_for = [](int i, const Camera& c) {
           Camera m = c;
           m.position.x = 1000.0 + i;  // e.g. the same path planned over another terrain
           return m;
         }});
  ExperimentOptions o;
  o.warmup_draws = 0;
  PathSource cams(path_of(3));
  const ExperimentResult r = e.run(cams, o);
  EXPECT_EQ(r.run("a").frames[2].ms, 20.0);
  EXPECT_EQ(r.run("b").frames[0].ms, 1000.0);
  EXPECT_EQ(r.run("b").frames[2].ms, 1002.0);
}

TEST(Experiment, RotatingParticipantsTakeTurnsTheOthersKeepTheirPlace) {
  std::vector<std::string> log;
  FakeRenderer ref("ref", 0, log), t("t", 0, log), a("a", 1, log), b("b", 2, log), c("c", 3, log);
  Experiment e;
  e.set_reference({.renderer = &ref, .name = "ref", .rotate = true});  // ignored: drawn first
  e.add({.renderer = &t, .name = "t"});
  e.add({.renderer = &a, .name = "a", .score = true, .rotate = true});
  e.add({.renderer = &b, .name = "b", .score = true, .rotate = true});
  e.add({.renderer = &c, .name = "c", .score = true, .rotate = true});
  ExperimentOptions o;
  o.warmup_draws = 0;
  o.scorer = byte_scorer;
  constexpr int kFrames = 60;
  PathSource cams(path_of(kFrames));
  const ExperimentResult r = e.run(cams, o);
  std::vector<std::string> draws;
  for (const std::string& l : log)
    if (l.size() > 5 && l.substr(l.size() - 5) == " draw")
      draws.push_back(l.substr(0, l.size() - 5));
  ASSERT_EQ(draws.size(), std::size_t(5 * kFrames));
  // Every frame: the reference, then t in its place, then a, b and c in some
  // order; over the run each of them is in each place, and each follows
  // each of the others (a cyclic shift would leave a after c only once a cycle).
  std::map<std::pair<std::string, int>, int> in_place;
  std::map<std::pair<std::string, std::string>, int> follows;
  std::string orders;
  for (int i = 0; i < kFrames; ++i) {
    const auto f = draws.begin() + 5 * i;
    EXPECT_EQ(f[0], "ref");
    EXPECT_EQ(f[1], "t");
    EXPECT_EQ(std::set<std::string>(f + 2, f + 5), (std::set<std::string>{"a", "b", "c"}));
    for (int p = 2; p < 5; ++p) in_place[{f[p], p}] += 1;
    follows[{f[3], f[2]}] += 1;
    follows[{f[4], f[3]}] += 1;
    orders += f[2] + f[3] + f[4];
  }
  for (const char* x : {"a", "b", "c"}) {
    for (int p = 2; p < 5; ++p) EXPECT_GE((in_place[{x, p}]), 8) << x << " in place " << p;
    for (const char* y : {"a", "b", "c"})
      if (std::string(x) != y) {
        EXPECT_GE((follows[{x, y}]), 8) << x << " after " << y;
      }
  }
  // The same orders on every run (a fixed seed).
  std::vector<std::string> again;
  FakeRenderer ref2("ref", 0, again), t2("t", 0, again), a2("a", 1, again), b2("b", 2, again),
      c2("c", 3, again);
  Experiment e2;
  e2.set_reference(ref2, "ref");
  e2.add({.renderer = &t2, .name = "t"});
  for (FakeRenderer* x : {&a2, &b2, &c2})
    e2.add({.renderer = x, .name = x->name(), .score = true, .rotate = true});
  PathSource cams2(path_of(kFrames));
  e2.run(cams2, o);
  EXPECT_EQ(again, log);
  // Each run still holds its own frames, in frame order, scored against the reference.
  ASSERT_EQ(r.runs.size(), 5u);
  for (std::size_t k : {2u, 3u, 4u}) {
    ASSERT_EQ(r.runs[k].frames.size(), std::size_t(kFrames)) << r.runs[k].name;
    for (int i = 0; i < kFrames; ++i) {
      EXPECT_EQ(r.runs[k].frames[std::size_t(i)].frame, i);
      ASSERT_TRUE(r.runs[k].frames[std::size_t(i)].quality);
      // The fake's byte is (x + offset) mod 256, x = 10 i: the difference wraps with it.
      const int offset = int(k) - 1, x = 10 * i;
      EXPECT_EQ(r.runs[k].frames[std::size_t(i)].quality->psnr,
                double((x + offset) % 256) - double(x % 256));
    }
  }
}

TEST(Fly, StreamingAndCollectingGiveTheSameStats) {
  std::vector<std::string> log;
  FakeRenderer a("a", 3, log);
  const std::vector<Camera> p = path_of(6);
  const std::vector<FrameStats> kept = fly(a, p, ReadBack::kColor);
  std::vector<FrameStats> streamed;
  int frames_seen = 0;
  fly(
      a, p, ReadBack::kColor, [&](int, const Frame& f) { frames_seen += !f.color.rgba.empty(); },
      [&](const FrameStats& s) { streamed.push_back(s); }, {});
  ASSERT_EQ(kept.size(), 6u);
  ASSERT_EQ(streamed.size(), 6u);
  EXPECT_EQ(frames_seen, 6) << "every frame read back in colour";
  for (std::size_t i = 0; i < kept.size(); ++i) {
    EXPECT_EQ(kept[i].frame, int(i));
    EXPECT_EQ(kept[i].frame, streamed[i].frame);
    EXPECT_EQ(kept[i].ms, 10.0 * double(i) + 3);
    EXPECT_EQ(kept[i].ms, streamed[i].ms);
    EXPECT_EQ(kept[i].cls, streamed[i].cls);
  }
}

}  // namespace
}  // namespace terrasprite
