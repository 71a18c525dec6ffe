// SPDX-License-Identifier: MIT
// The one experiment driver: a camera source flown through several renderers
// frame by frame (interleaved, so machine noise hits them alike), each draw
// timed on its own, read-back and scoring outside the timed spans, typed
// results out. Benches, the demo and `render` all run through it; JSON, plots
// and HTML are written from its results at the edge.
#pragma once
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "terrasprite/camera/camera.h"
#include "terrasprite/camera/renderer.h"
#include "terrasprite/common/stats.h"

namespace terrasprite {

/// Where cameras come from: a fixed path, a live input, a prediction.
class CameraSource {
 public:
  virtual ~CameraSource() = default;
  /// The camera of output frame `frame` (0, 1, 2, ... in order), or
  /// std::nullopt once the source has ended.
  virtual std::optional<Camera> camera(int frame) = 0;
  /// How many frames it gives, or -1 when that is not known (a live input).
  virtual int frames() const = 0;
};

/// A fixed path: its cameras in order.
class PathSource final : public CameraSource {
 public:
  explicit PathSource(std::vector<Camera> path) : path_(std::move(path)) {}
  std::optional<Camera> camera(int frame) override {
    if (frame < 0 || frame >= int(path_.size())) return std::nullopt;
    return path_[std::size_t(frame)];
  }
  int frames() const override { return int(path_.size()); }
  const std::vector<Camera>& path() const { return path_; }

 private:
  std::vector<Camera> path_;
};

/// PSNR is capped here: identical images (a keyframe is the reference frame
/// itself) would otherwise score +inf.
inline constexpr double kPsnrCapDb = 100.0;

/// Image quality of a frame against the reference frame.
struct QualityScore {
  double psnr = kPsnrCapDb;  ///< dB over R, G, B, capped at kPsnrCapDb
  double ssim = 1.0;         ///< Wang SSIM on luma
  double flip = -1.0;        ///< mean LDR-FLIP; -1 when not computed
  /// A scorer's further figures (e.g. "ssim_terrain": SSIM masked to the
  /// reference's terrain pixels); RendererRun::quality summarises them by key.
  std::map<std::string, double> figures;
};

/// One renderer's figures for one frame.
struct FrameResult {
  int frame = 0;
  FrameClass cls = FrameClass::kFull;
  double ms = 0;       ///< the draw's time, pipeline drained
  double gpu_ms = -1;  ///< GL timer query, -1 = no result
  long long triangles = 0;
  std::optional<QualityScore> quality;  ///< against the reference frame, when scored
  /// The renderer's own figures (error_px, tiles_loaded, hole_fraction, ...):
  /// later renderers add keys without changing the driver.
  std::map<std::string, double> counters;
  std::map<std::string, std::string> tags;  ///< the same for text (e.g. a keyframe's trigger)
};

/// All frames one renderer drew in a run, with summaries.
struct RendererRun {
  std::string name;
  std::vector<FrameResult> frames;

  /// Draw time of every frame (or of class `cls` only).
  Summary ms(std::optional<FrameClass> cls = std::nullopt) const;
  /// GL timer times, "no result" (-1) skipped.
  Summary gpu_ms(std::optional<FrameClass> cls = std::nullopt) const;
  /// A quality figure ("psnr", "ssim", "flip", or a key of QualityScore::figures)
  /// over the scored frames (of class `cls`); non-finite values are skipped.
  Summary quality(const std::string& metric, std::optional<FrameClass> cls = std::nullopt) const;
  /// A counter over the frames that have it.
  Summary counter(const std::string& key, std::optional<FrameClass> cls = std::nullopt) const;
  int count(FrameClass cls) const;
};

struct ExperimentResult {
  int frames = 0;                 ///< camera frames flown
  std::vector<RendererRun> runs;  ///< the reference first (when set), then in the order added
  /// The run named `name`; throws std::out_of_range when none is.
  const RendererRun& run(const std::string& name) const;
};

/// Scores `test` against `reference` (both read back in colour; depth too
/// when the participant asked for it).
using Scorer = std::function<QualityScore(const Frame& reference, const Frame& test)>;
/// PSNR + SSIM (luma), and FLIP when `with_flip`; identical images score
/// {kPsnrCapDb, 1, 0} without computing anything.
Scorer default_scorer(bool with_flip);

/// One renderer in an experiment.
struct Participant {
  Renderer* renderer = nullptr;     ///< not owned; must outlive run()
  std::string name;                 ///< defaults to renderer->name()
  bool score = false;               ///< score against the reference on scored frames
  int every = 1;                    ///< draw only every n-th frame (a slow baseline)
  int warmup_draws = -1;            ///< untimed draws before the run; -1: the options' count
  ReadBack read = ReadBack::kNone;  ///< read back even when not scoring (e.g. to save frames)
  /// Called once the warm-up draws are done (e.g. to forget a warm-up keyframe).
  std::function<void()> after_warmup;
  /// Adds the renderer's own counters and tags to a frame's result; called
  /// right after the draw, outside the timed span.
  std::function<void(const Frame&, FrameResult&)> annotate;
  /// The camera this participant draws for frame i of the source (default:
  /// the source's camera), e.g. the same path planned over another terrain in
  /// a terrain-size sweep. A mapped participant should not be scored: the
  /// reference draws the source's camera.
  std::function<Camera(int frame, const Camera& source)> camera_for;
  /// Takes turns with the other rotating participants: they share their
  /// places in the frame's order, shuffled every frame (with a fixed seed:
  /// the same orders every run), so none always draws right after the same
  /// one. A draw's time depends on what ran just before it (in the hybrid
  /// walkthrough the spread of a scenario's frame times, which sets its
  /// budget, depends on which scenario it follows). The reference
  /// never rotates (it is drawn first: the others are scored against it).
  bool rotate = false;
};

struct ExperimentOptions {
  int warmup_draws = 1;  ///< untimed draws of the first camera per renderer (shaders, first use)
  int score_every = 1;   ///< score (and draw the reference) on every n-th frame
  Scorer scorer;         ///< empty: default_scorer(true)
  /// Every frame of every renderer once read back and scored (the name is the
  /// participant's; the reference's frame comes first): save it, keep it.
  std::function<void(int frame, const std::string& name, const Frame&)> on_frame;
  /// Every frame's result as soon as it is complete (after on_frame).
  std::function<void(const std::string& name, const FrameResult&)> on_result;
  /// Keep every FrameResult in the returned runs (their summaries need them).
  /// False: the runs come back without frames and memory stays flat however
  /// long the run; take the results from on_result instead.
  bool keep_frames = true;
  std::function<void(int done, int total)> progress;
};

/// Runs participants over a camera source. Per frame: the reference (on
/// scored frames) draws and is read back, then each participant in order
/// (rotating ones take turns in their places, Participant::rotate)
/// draws (timed inside the renderer), is read back where needed, scored,
/// annotated and handed to on_frame; nothing but the draw is in a timed span.
class Experiment {
 public:
  /// The renderer the scored participants are compared with, drawn (and
  /// timed, and recorded as the first run) on scored frames and read back as
  /// `read` (colour at least). Optional: without it nothing is scored.
  void set_reference(Renderer& renderer, std::string name = "", ReadBack read = ReadBack::kColor);
  /// The same with every participant setting (score and every are ignored).
  void set_reference(Participant participant);
  void add(Participant participant);
  ExperimentResult run(CameraSource& cameras, const ExperimentOptions& options);

 private:
  std::optional<Participant> reference_;
  std::vector<Participant> participants_;
};

}  // namespace terrasprite
