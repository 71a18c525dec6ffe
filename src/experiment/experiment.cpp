// SPDX-License-Identifier: MIT
#include "terrasprite/experiment/experiment.h"

#include <algorithm>
#include <random>
#include <stdexcept>

#include "terrasprite/quality/quality.h"

namespace terrasprite {

namespace {

template <typename Value>
Summary summarize_frames(const std::vector<FrameResult>& frames, std::optional<FrameClass> cls,
                         Value value, bool valid_only = false) {
  std::vector<double> v;
  for (const FrameResult& f : frames)
    if (!cls || f.cls == *cls)
      if (std::optional<double> x = value(f)) v.push_back(*x);
  return valid_only ? summarize_valid(v) : summarize(v);
}

FrameResult result_of(int frame, const Frame& f) {
  FrameResult r;
  r.frame = frame;
  r.cls = f.cls;
  r.ms = f.ms;
  r.gpu_ms = f.gpu_ms;
  r.triangles = f.triangles;
  return r;
}

}  // namespace

Summary RendererRun::ms(std::optional<FrameClass> cls) const {
  return summarize_frames(frames, cls, [](const FrameResult& f) { return std::optional(f.ms); });
}

Summary RendererRun::gpu_ms(std::optional<FrameClass> cls) const {
  return summarize_frames(
      frames, cls, [](const FrameResult& f) { return std::optional(f.gpu_ms); }, true);
}

Summary RendererRun::quality(const std::string& metric, std::optional<FrameClass> cls) const {
  return summarize_frames(frames, cls, [&](const FrameResult& f) -> std::optional<double> {
    if (!f.quality) return std::nullopt;
    if (metric == "psnr") return f.quality->psnr;
    if (metric == "ssim") return f.quality->ssim;
    if (metric == "flip") {
      if (f.quality->flip < 0) return std::nullopt;
      return f.quality->flip;
    }
    auto it = f.quality->figures.find(metric);
    if (it == f.quality->figures.end()) return std::nullopt;
    return it->second;
  });
}

Summary RendererRun::counter(const std::string& key, std::optional<FrameClass> cls) const {
  return summarize_frames(frames, cls, [&](const FrameResult& f) -> std::optional<double> {
    auto it = f.counters.find(key);
    if (it == f.counters.end()) return std::nullopt;
    return it->second;
  });
}

int RendererRun::count(FrameClass cls) const {
  return int(std::count_if(frames.begin(), frames.end(),
                           [&](const FrameResult& f) { return f.cls == cls; }));
}

const RendererRun& ExperimentResult::run(const std::string& name) const {
  for (const RendererRun& r : runs)
    if (r.name == name) return r;
  throw std::out_of_range("experiment has no run named " + name);
}

Scorer default_scorer(bool with_flip) {
  return [with_flip](const Frame& reference, const Frame& test) {
    QualityScore s;
    if (reference.color.rgba == test.color.rgba) {
      s.flip = with_flip ? 0.0 : -1.0;
      return s;
    }
    s.psnr = std::min(quality::psnr(reference.color.view(), test.color.view()).rgb, kPsnrCapDb);
    quality::SsimOptions so;
    so.channels = false;
    s.ssim = quality::ssim(reference.color.view(), test.color.view(), so).ssim;
    s.flip = with_flip ? quality::flip(reference.color.view(), test.color.view()).mean : -1.0;
    return s;
  };
}

void Experiment::set_reference(Renderer& renderer, std::string name, ReadBack read) {
  Participant p;
  p.renderer = &renderer;
  p.name = std::move(name);
  p.read = read;
  set_reference(std::move(p));
}

void Experiment::set_reference(Participant p) {
  if (p.name.empty()) p.name = p.renderer->name();
  p.read = p.read | ReadBack::kColor;
  reference_ = std::move(p);
}

void Experiment::add(Participant participant) {
  if (participant.name.empty()) participant.name = participant.renderer->name();
  participants_.push_back(std::move(participant));
}

ExperimentResult Experiment::run(CameraSource& cameras, const ExperimentOptions& o) {
  const Scorer scorer = o.scorer ? o.scorer : default_scorer(true);
  const int score_every = std::max(1, o.score_every);
  std::vector<Participant*> all;
  if (reference_) all.push_back(&*reference_);
  for (Participant& p : participants_) all.push_back(&p);

  ExperimentResult result;
  for (Participant* p : all) result.runs.push_back({p->name, {}});
  if (std::optional<Camera> first = cameras.camera(0))
    for (Participant* p : all) {
      const int draws = p->warmup_draws >= 0 ? p->warmup_draws : o.warmup_draws;
      const Camera c = p->camera_for ? p->camera_for(0, *first) : *first;
      for (int k = 0; k < draws; ++k) p->renderer->draw(c);
      if (p->after_warmup) p->after_warmup();
    }

  const int total = cameras.frames();
  // One frame per participant, drawn into again each time (draw_into): a CPU
  // renderer reuses its buffers instead of allocating a frame per draw. The
  // reference's frame is frames[0], read by the others' scorers.
  std::vector<Frame> frames(std::max<std::size_t>(1, all.size()));
  std::vector<std::size_t> slots;  // places the rotating participants share
  for (std::size_t k = reference_ ? 1 : 0; k < all.size(); ++k)
    if (all[k]->rotate) slots.push_back(k);
  std::vector<std::size_t> order(all.size()), turn = slots;
  // A fixed seed: the same order every run. Shuffled, not shifted: a cyclic
  // shift keeps who follows whom in all but one frame of each cycle.
  std::mt19937 rng(1);
  for (int i = 0;; ++i) {
    std::optional<Camera> camera = cameras.camera(i);
    if (!camera) break;
    const bool scored = reference_ && i % score_every == 0;
    const Frame& ref = frames[0];
    for (std::size_t k = 0; k < all.size(); ++k) order[k] = k;
    for (std::size_t j = turn.size(); j > 1; --j) std::swap(turn[j - 1], turn[rng() % j]);
    for (std::size_t j = 0; j < slots.size(); ++j) order[slots[j]] = turn[j];
    for (std::size_t place = 0; place < all.size(); ++place) {
      const std::size_t k = order[place];
      Participant& p = *all[k];
      const bool is_ref = reference_ && k == 0;
      if (is_ref ? !scored : i % std::max(1, p.every) != 0) continue;
      Frame& f = frames[k];
      p.renderer->draw_into(p.camera_for ? p.camera_for(i, *camera) : *camera, f);
      FrameResult r = result_of(i, f);
      if (p.annotate) p.annotate(f, r);
      const bool score = !is_ref && scored && p.score;
      const ReadBack read = score ? (p.read | ReadBack::kColor) : p.read;
      // The reference's read always holds colour (set_reference adds it).
      if (read != ReadBack::kNone) p.renderer->read_back(f, read);
      if (score) r.quality = scorer(ref, f);
      if (o.on_frame) o.on_frame(i, p.name, f);
      if (o.on_result) o.on_result(p.name, r);
      if (o.keep_frames) result.runs[k].frames.push_back(std::move(r));
    }
    result.frames = i + 1;
    if (o.progress) o.progress(i + 1, total);
  }
  return result;
}

}  // namespace terrasprite
