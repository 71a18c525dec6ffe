// SPDX-License-Identifier: MIT
#include "viewer/viewer.h"

#include <epoxy/gl.h>
// epoxy first: it replaces the GL header GLFW would include.
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <filesystem>
#include <future>
#include <optional>
#include <set>

#include "terrasprite/common/error.h"
#include "terrasprite/common/image.h"
#include "terrasprite/output/output_file.h"
#include "terrasprite/terrain/image_io.h"
#include "viewer/frame_view.h"
#include "viewer/panel.h"
#include "viewer/path_recorder.h"
#include "viewer/window.h"

namespace terrasprite::viewer {

namespace {

double seconds(Clock::duration d) {
  return std::chrono::duration<double>(d).count();
}

/// A scripted event waiting for the first frame that shows it.
struct Pending {
  std::size_t index;         // into RunStats::events
  std::uint64_t generation;  // input generation after it arrived
  Clock::time_point at;
  std::string screenshot;  // non-empty: write the window to this PNG on that frame
};

/// Reads the window's back buffer (panel included), as GL leaves it: rows bottom-up.
Image read_window(int w, int h) {
  Image img(w, h);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, img.rgba.data());
  return img;
}

/// Flips a read_window() image to top-down rows, makes it opaque and writes
/// the PNG by the output-file rules.
void write_window_png(Image img, const std::string& file, OutputPolicy policy) {
  const int w = img.width, h = img.height;
  std::vector<std::uint8_t> row(std::size_t(w) * 4);
  for (int y = 0; y < h / 2; ++y) {  // GL's rows are bottom-up
    std::swap_ranges(img.px(0, y), img.px(0, y) + row.size(), img.px(0, h - 1 - y));
  }
  for (std::size_t i = 3; i < img.rgba.size(); i += 4) img.rgba[i] = 255;
  write_output_file(file, policy, [&img](const std::string& tmp) { save_png(img, tmp); });
}

std::string free_name(const std::string& dir, const char* stem, const char* ext) {
  for (int i = 0;; ++i) {
    std::string f =
        (std::filesystem::path(dir) / fmt::format("{}_{:03d}.{}", stem, i, ext)).string();
    if (!std::filesystem::exists(f)) return f;
  }
}

class Loop {
 public:
  Loop(const Heightfield& h, const Camera& start, const ViewerOptions& o,
       const ViewRendererFactory& factory)
      : o_(o),
        heights_(h),
        win_(o.width, o.height, "terrasprite view"),
        fly_(h, start, o.fly),
        worker_(factory, o.share_context && win_.has_shared_context()
                             ? ContextFactory([this] { return win_.adopt_shared_context(); })
                             : ContextFactory()),
        settings_(o.settings) {
    stats_.mode = o.settings.mode;
    stats_.width = o.width;
    stats_.height = o.height;
  }

  RunStats run();

 private:
  void inject_script(double t);
  void handle(const ArrivedEvent& e);
  void move_camera(double t, double dt);
  void present(std::optional<RenderedFrame>& f, Clock::time_point now);
  void act(const PanelActions& a);
  bool done(double t) const;
  void begin(Clock::time_point first_frame);
  void start_recording(const std::string& file);
  void stop_recording();
  void start_playing(const std::string& file);
  OutputPolicy policy_for(const std::string& file);

  const ViewerOptions& o_;
  const Heightfield& heights_;
  Window win_;
  FrameView view_;
  FlyController fly_;
  RenderWorker worker_;
  LiveSettings settings_;
  RunStats stats_;
  PanelInfo info_;
  bool help_ = false, quit_ = false, begun_ = false;
  Clock::time_point t0_ = Clock::now(), last_new_swap_{}, last_swap_{}, shown_at_{};
  std::uint64_t generation_ = 0;
  std::size_t next_script_ = 0;
  std::vector<Pending> pending_;
  std::string screenshot_request_;
  std::optional<PathRecorder> recorder_;
  std::string record_file_;
  double record_t0_ = 0;
  std::optional<PathPlayer> player_;
  double play_t0_ = 0;
  std::optional<Image> difference_;  // of the last compare
  double last_script_t_ = 0;
  // Screenshots are read before the swap but encoded on their own threads after
  // it: encoding a PNG takes many frames' time, which would otherwise delay
  // the swap and count against the latency of every event that frame shows.
  std::vector<std::pair<Image, std::string>> shots_;
  std::vector<std::future<void>> writes_;
  std::set<std::string> written_;  // files this run wrote (or is writing)
};

// The user's policy, and any file this run wrote may be written again
// (a script's repeated screenshot, a recording stopped twice).
OutputPolicy Loop::policy_for(const std::string& file) {
  OutputPolicy p = o_.output;
  p.overwrite = p.overwrite || written_.count(file) > 0;
  written_.insert(file);
  return p;
}

void Loop::start_recording(const std::string& file) {
  recorder_.emplace(o_.record_every_s);
  record_file_ = file;
  record_t0_ = seconds(Clock::now() - t0_);
}

void Loop::stop_recording() {
  if (!recorder_) return;
  recorder_->close(seconds(Clock::now() - t0_) - record_t0_, fly_.camera());
  recorder_->write(record_file_, policy_for(record_file_));
  info_.message = fmt::format("path written: {} ({} keyframes)", record_file_, recorder_->size());
  recorder_.reset();
}

void Loop::start_playing(const std::string& file) {
  player_.emplace(file, heights_, double(o_.width) / o_.height);
  play_t0_ = seconds(Clock::now() - t0_);
}

// The run's clock starts when the first frame is on screen, so start-up (GL
// context, meshes) is not counted against the first events.
void Loop::begin(Clock::time_point first_frame) {
  begun_ = true;
  t0_ = first_frame;
  if (!o_.record.empty()) start_recording(o_.record);
  if (!o_.play.empty()) {
    start_playing(o_.play);
    fly_.set_camera(player_->camera_at(0));
  }
  stats_.camera_start = fly_.camera();
}

void Loop::inject_script(double t) {
  while (next_script_ < o_.script.size() && o_.script[next_script_].t <= t) {
    const ScriptEvent& s = o_.script[next_script_++];
    stats_.events.push_back({s.t, -1});
    Pending p{stats_.events.size() - 1, 0, Clock::now(), ""};
    if (s.event.kind == InputKind::kScreenshot) {
      p.screenshot = s.event.file;
    } else {
      win_.inject(s.event);
      for (const ArrivedEvent& e : win_.drain()) handle(e);
    }
    p.generation = generation_;
    pending_.push_back(p);
  }
}

void Loop::handle(const ArrivedEvent& a) {
  generation_ = a.seq;
  const InputEvent& e = a.event;
  if (e.kind == InputKind::kKey && e.action == GLFW_PRESS) {
    switch (e.key) {
      case GLFW_KEY_ESCAPE:
        quit_ = true;
        return;
      case GLFW_KEY_F1:
        help_ = !help_;
        return;
      case GLFW_KEY_F2:
        screenshot_request_ = free_name(o_.screenshot_dir, "view", "png");
        return;
      case GLFW_KEY_F3:
        act({.compare = true});
        return;
      case GLFW_KEY_F4:
        act({.toggle_difference = true});
        return;
      case GLFW_KEY_F5:
        act({.toggle_record = true});
        return;
      case GLFW_KEY_F6:
        act({.play = true});
        return;
      case GLFW_KEY_1:
        settings_.mode = RenderMode::kFull;
        return;
      case GLFW_KEY_2:
        settings_.mode = RenderMode::kLod;
        return;
      case GLFW_KEY_3:
        settings_.mode = RenderMode::kSprite;
        return;
      case GLFW_KEY_4:
        settings_.mode = RenderMode::kVoxel;
        return;
      default:
        break;
    }
  }
  if (player_ && e.kind == InputKind::kKey) return;  // the path flies; ESCAPE still quits
  fly_.handle(e);
}

void Loop::act(const PanelActions& a) {
  if (a.screenshot) screenshot_request_ = free_name(o_.screenshot_dir, "view", "png");
  if (a.compare && !info_.comparing) {
    worker_.request_compare();
    info_.comparing = true;
  }
  if (a.toggle_difference && difference_) {
    info_.show_difference = !info_.show_difference;
    if (info_.show_difference) view_.upload(*difference_);
  }
  if (a.toggle_record) {
    if (recorder_)
      stop_recording();
    else
      start_recording(record_file_.empty() ? free_name(o_.screenshot_dir, "view_path", "json")
                                           : record_file_);
  }
  if (a.play && !record_file_.empty() && std::filesystem::exists(record_file_)) {
    if (recorder_) stop_recording();
    start_playing(record_file_);
  }
}

void Loop::move_camera(double t, double dt) {
  if (player_) {
    const double pt = t - play_t0_;
    fly_.set_camera(player_->camera_at(pt));
    if (pt > player_->duration()) player_.reset();
  } else {
    fly_.update(dt);
  }
  if (recorder_) recorder_->offer(t - record_t0_, fly_.camera());
}

void Loop::present(std::optional<RenderedFrame>& f, Clock::time_point now) {
  if (f && f->comparison) {
    const Comparison& c = *f->comparison;
    info_.compared = true;
    info_.comparing = false;
    info_.psnr = c.psnr;
    info_.ssim = c.ssim;
    info_.flip = c.flip;
    info_.compared_mode = c.mode;
    info_.message = fmt::format("compared {} with full: PSNR {:.2f} dB, SSIM {:.4f}, FLIP {:.4f}",
                                to_string(c.mode), c.psnr, c.ssim, c.flip);
    stats_.comparisons.push_back({c.mode, c.psnr, c.ssim, c.flip});
    difference_ = std::move(f->comparison->difference);
    if (info_.show_difference) view_.upload(*difference_);
  }
  if (f) {
    if (info_.show_difference) {
      // the difference image stays on screen until toggled off
    } else if (f->texture) {
      view_.show(f->texture);  // drawn by the worker in a shared context: no copy
    } else {
      view_.upload(f->frame.color);
    }
    info_.render_ms = f->frame.ms;
    info_.triangles = f->frame.triangles;
    info_.cls =
        std::string(frame_class_name(f->frame.cls)) + (f->landed ? " (keyframe landed)" : "");
    info_.error_px = f->error_px;
    info_.keyframes = f->keyframes;
    info_.device = f->device;
    shown_at_ = now;
  }
  info_.building = worker_.building();
  info_.stale_ms = seconds(now - shown_at_) * 1000;
  info_.camera = fly_.camera();
  info_.speed_mps = fly_.speed_mps();
  info_.clearance_m = fly_.clearance_m();
  info_.orbit = fly_.orbiting();
  info_.recording = recorder_.has_value();
  info_.playing = player_.has_value();
  info_.captured = win_.cursor_captured();

  const auto [fw, fh] = win_.framebuffer_size();
  view_.draw(fw, fh);
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  act(draw_panel(info_, settings_));
  if (help_) draw_help();
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  if (f) {
    for (Pending& p : pending_)
      if (!p.screenshot.empty() && p.generation <= f->generation)
        shots_.emplace_back(read_window(fw, fh), p.screenshot);
  }
  if (!screenshot_request_.empty()) {
    shots_.emplace_back(read_window(fw, fh), screenshot_request_);
    info_.message = "screenshot: " + screenshot_request_;
    screenshot_request_.clear();
  }
  win_.swap();
  const Clock::time_point swapped = Clock::now();
  last_swap_ = swapped;
  for (auto& [img, file] : shots_)
    writes_.push_back(
        std::async(std::launch::async, write_window_png, std::move(img), file, policy_for(file)));
  shots_.clear();
  if (!f) return;
  // Book-keeping of a newly shown frame: its interval and the events it shows.
  if (stats_.frames > 0) {
    const double ms = seconds(swapped - last_new_swap_) * 1000;
    stats_.frame_ms.push_back(ms);
    info_.history.push_back({float(ms), f->frame.cls == FrameClass::kKey ||
                                            f->frame.cls == FrameClass::kVoxel || f->landed});
    if (info_.history.size() > 240) info_.history.pop_front();
    double sum = 0;
    for (const auto& s : info_.history) sum += s.ms;
    info_.fps = sum > 0 ? 1000.0 * double(info_.history.size()) / sum : 0;
  }
  stats_.render_ms.push_back(f->frame.ms);
  ++stats_.classes[frame_class_name(f->frame.cls)];
  stats_.keyframes_landed += f->landed;
  if (f->landed && f->keyframes) stats_.keyframe_ms.push_back(f->keyframes->last_keyframe_ms);
  if (!begun_) begin(swapped);
  ++stats_.frames;
  last_new_swap_ = swapped;
  std::erase_if(pending_, [&](const Pending& p) {
    if (p.generation > f->generation) return false;
    stats_.events[p.index].latency_ms = seconds(swapped - p.at) * 1000;
    return true;
  });
}

bool Loop::done(double t) const {
  if (quit_ || win_.should_close()) return true;
  if (o_.frames > 0 && stats_.frames >= o_.frames) return true;
  if (o_.scripted && next_script_ >= o_.script.size() && t >= last_script_t_ + 1.0) return true;
  return false;
}

RunStats Loop::run() {
  if (!o_.script.empty()) last_script_t_ = o_.script.back().t;
  Clock::time_point last = Clock::now();
  shown_at_ = last;
  for (;;) {
    const Clock::time_point now = Clock::now();
    const double t = seconds(now - t0_);
    if (begun_ && done(t)) break;
    if (!begun_ && (quit_ || win_.should_close())) break;
    win_.poll();
    for (const ArrivedEvent& e : win_.drain()) handle(e);
    if (begun_) {
      inject_script(t);
      move_camera(t, seconds(now - last));
    }
    last = now;
    worker_.request(fly_.camera(), generation_, settings_);
    std::optional<RenderedFrame> f = worker_.take();
    // A new frame is shown at once; without one the panel still redraws at ~30 Hz.
    if (f || seconds(now - last_swap_) > 0.033) {
      present(f, now);
    } else {
      double wait = 0.004;
      if (next_script_ < o_.script.size())
        wait = std::clamp(o_.script[next_script_].t - t, 0.0, wait);
      worker_.wait(wait);
    }
  }
  if (recorder_) stop_recording();
  for (std::future<void>& w : writes_) w.get();  // a failed write throws here
  stats_.camera_end = fly_.camera();
  stats_.mode = settings_.mode;
  return stats_;
}

}  // namespace

void check_view_outputs(const ViewerOptions& o) {
  if (!std::filesystem::is_directory(o.screenshot_dir))
    throw InputError(fmt::format("--screenshot-dir {}: not a directory", o.screenshot_dir));
  if (!o.record.empty()) check_output_file(o.record, o.output);
  for (const ScriptEvent& s : o.script)
    if (s.event.kind == InputKind::kScreenshot) check_output_file(s.event.file, o.output);
}

RunStats run_viewer(const Heightfield& heights, const Camera& start, const ViewerOptions& options,
                    const ViewRendererFactory& factory) {
  check_view_outputs(options);
  Loop loop(heights, start, options, factory);
  return loop.run();
}

}  // namespace terrasprite::viewer
