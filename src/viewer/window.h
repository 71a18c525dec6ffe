// SPDX-License-Identifier: MIT
// The viewer's window: GLFW (OpenGL 4.5 core), Dear ImGui on top, and the
// input layer its callbacks feed. Scripted events enter through the very same
// callbacks (inject), so a script exercises what a user's hands would.
#pragma once
#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "terrasprite/gl/gl_context.h"
#include "viewer/input_event.h"

struct GLFWwindow;

namespace terrasprite::viewer {

using Clock = std::chrono::steady_clock;

/// An input event as it arrived, numbered in arrival order from 1.
struct ArrivedEvent {
  InputEvent event;
  std::uint64_t seq = 0;
  Clock::time_point at;
};

/// A GLFW window with a current OpenGL 4.5 core context (swap interval 0) and
/// an ImGui context with its GLFW and OpenGL 3 backends. One per process.
/// Throws DeviceError with one line when there is no display or no GL 4.5
/// core context (run under `xvfb-run -a` on a machine without a display).
class Window {
 public:
  Window(int width, int height, const std::string& title);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  GLFWwindow* glfw() const { return window_; }
  /// Whether a second context sharing objects with the window's exists (a
  /// hidden window, made with the window).
  bool has_shared_context() const { return shared_ != nullptr; }
  /// Makes that second context current on the calling thread (the render
  /// worker's) and wraps it; the window must outlive it, and it must be
  /// released (GlContext::release_current) before the window is destroyed.
  /// Its create_shared() hands out a third context of the same share group
  /// (another hidden window, made on the main thread with the window, since
  /// GLFW makes windows only there), one holder at a time: the LOD-sprite
  /// renderer's keyframe worker. It throws DeviceError while that one is held.
  std::unique_ptr<GlContext> adopt_shared_context();
  bool should_close() const;
  void poll();  ///< delivers pending window-system events to the callbacks
  void swap();
  std::pair<int, int> framebuffer_size() const;

  /// Delivers `e` (key, mouse motion, button, wheel) through the GLFW
  /// callbacks, as GLFW would: mouse motion becomes a cursor position
  /// `dx, dy` away from the last one.
  void inject(const InputEvent& e);
  /// Events that arrived since the last call, in order. Keyboard events
  /// ImGui wants (a text field has focus) are not included.
  std::vector<ArrivedEvent> drain();

  /// Mouse look follows the cursor while captured (the default; TAB toggles
  /// it so the panel can be used with the mouse) or while the left button is
  /// held over the view.
  bool cursor_captured() const { return captured_; }
  void set_cursor_captured(bool on);

  // GLFW callbacks (public for the C trampolines).
  void on_key(int key, int action);
  void on_cursor(double x, double y);
  void on_button(int button, int action);
  void on_scroll(double dx, double dy);

 private:
  void push(InputEvent e);

  GLFWwindow* window_ = nullptr;
  GLFWwindow* shared_ = nullptr;     // hidden, sharing objects with window_
  GLFWwindow* keyframes_ = nullptr;  // hidden too: the keyframe worker's context
  std::atomic<bool> keyframes_held_{false};
  std::vector<ArrivedEvent> pending_;
  std::uint64_t next_seq_ = 1;
  bool captured_ = true, left_down_ = false, have_cursor_ = false;
  double cursor_x_ = 0, cursor_y_ = 0;
};

}  // namespace terrasprite::viewer
