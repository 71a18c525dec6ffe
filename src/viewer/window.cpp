// SPDX-License-Identifier: MIT
#include "viewer/window.h"

#include <epoxy/gl.h>
// epoxy first: it replaces the GL header GLFW would include.
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <fmt/format.h>
#include <imgui.h>

#include <utility>

#include "terrasprite/common/error.h"

namespace terrasprite::viewer {

namespace {

Window* owner(GLFWwindow* w) {
  return static_cast<Window*>(glfwGetWindowUserPointer(w));
}

void key_cb(GLFWwindow* w, int key, int scancode, int action, int mods) {
  ImGui_ImplGlfw_KeyCallback(w, key, scancode, action, mods);
  owner(w)->on_key(key, action);
}
void cursor_cb(GLFWwindow* w, double x, double y) {
  owner(w)->on_cursor(x, y);
}
void button_cb(GLFWwindow* w, int button, int action, int mods) {
  ImGui_ImplGlfw_MouseButtonCallback(w, button, action, mods);
  owner(w)->on_button(button, action);
}
void scroll_cb(GLFWwindow* w, double dx, double dy) {
  ImGui_ImplGlfw_ScrollCallback(w, dx, dy);
  owner(w)->on_scroll(dx, dy);
}
void char_cb(GLFWwindow* w, unsigned int c) {
  ImGui_ImplGlfw_CharCallback(w, c);
}

std::string glfw_error() {
  const char* d = nullptr;
  glfwGetError(&d);
  return d ? d : "unknown GLFW error";
}

}  // namespace

Window::Window(int width, int height, const std::string& title) {
  if (!glfwInit())
    throw DeviceError(
        fmt::format("view: no display ({}); run under xvfb-run -a without one", glfw_error()));
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  // EGL first (the renderers' own API; Mesa shares it between threads without
  // GLX's X round trips), then the platform's native API (GLX).
  glfwWindowHint(GLFW_CONTEXT_CREATION_API, GLFW_EGL_CONTEXT_API);
  window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!window_) {
    glfwWindowHint(GLFW_CONTEXT_CREATION_API, GLFW_NATIVE_CONTEXT_API);
    window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  }
  if (!window_) {
    const std::string why = glfw_error();
    glfwTerminate();
    throw DeviceError(fmt::format("view: cannot open an OpenGL 4.5 core window ({})", why));
  }
  glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
  shared_ = glfwCreateWindow(16, 16, "terrasprite render", nullptr, window_);  // null: none
  if (shared_) keyframes_ = glfwCreateWindow(16, 16, "terrasprite keyframes", nullptr, window_);
  glfwSetWindowUserPointer(window_, this);
  glfwMakeContextCurrent(window_);
  glfwSwapInterval(0);
  glfwSetKeyCallback(window_, key_cb);
  glfwSetCursorPosCallback(window_, cursor_cb);
  glfwSetMouseButtonCallback(window_, button_cb);
  glfwSetScrollCallback(window_, scroll_cb);
  glfwSetCharCallback(window_, char_cb);
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini litter in the working directory
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(window_, false);  // our callbacks forward to it
  ImGui_ImplOpenGL3_Init("#version 450 core");
  set_cursor_captured(true);
}

Window::~Window() {
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  if (keyframes_) glfwDestroyWindow(keyframes_);
  if (shared_) glfwDestroyWindow(shared_);
  glfwDestroyWindow(window_);
  glfwTerminate();
}

std::unique_ptr<GlContext> Window::adopt_shared_context() {
  GLFWwindow* w = shared_;
  glfwMakeContextCurrent(w);
  GlContext::External e;
  e.make_current = [w] { glfwMakeContextCurrent(w); };
  e.release_current = [] { glfwMakeContextCurrent(nullptr); };
  e.create_shared = [this]() -> std::unique_ptr<GlContext> {
    if (!keyframes_ || keyframes_held_.exchange(true))
      throw DeviceError("view: no further GL context shared with the window is free");
    GLFWwindow* k = keyframes_;
    GlContext::External x;
    x.make_current = [k] { glfwMakeContextCurrent(k); };
    x.release_current = [] { glfwMakeContextCurrent(nullptr); };
    x.destroy = [this] { keyframes_held_ = false; };
    return GlContext::adopt(std::move(x));  // checks the caller's context: same hints, same GL
  };
  return GlContext::adopt(std::move(e));
}

bool Window::should_close() const {
  return glfwWindowShouldClose(window_);
}
void Window::poll() {
  glfwPollEvents();
}
void Window::swap() {
  glfwSwapBuffers(window_);
}

std::pair<int, int> Window::framebuffer_size() const {
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_, &w, &h);
  return {w, h};
}

void Window::set_cursor_captured(bool on) {
  captured_ = on;
  glfwSetInputMode(window_, GLFW_CURSOR, on ? GLFW_CURSOR_DISABLED : GLFW_CURSOR_NORMAL);
  have_cursor_ = false;  // the mode change may jump the cursor: no look from that jump
}

void Window::inject(const InputEvent& e) {
  switch (e.kind) {
    case InputKind::kKey:
      key_cb(window_, e.key, glfwGetKeyScancode(e.key), e.action, 0);
      break;
    case InputKind::kMouse:
      if (!have_cursor_) on_cursor(cursor_x_, cursor_y_);  // anchor: no jump
      cursor_cb(window_, cursor_x_ + e.dx, cursor_y_ + e.dy);
      break;
    case InputKind::kButton:
      button_cb(window_, e.button, e.action, 0);
      break;
    case InputKind::kWheel:
      scroll_cb(window_, e.dx, e.dy);
      break;
    case InputKind::kScreenshot:
      break;
  }
}

std::vector<ArrivedEvent> Window::drain() {
  return std::exchange(pending_, {});
}

void Window::push(InputEvent e) {
  pending_.push_back({std::move(e), next_seq_++, Clock::now()});
}

void Window::on_key(int key, int action) {
  if (ImGui::GetIO().WantCaptureKeyboard && !captured_) return;
  if (key == GLFW_KEY_TAB && action == GLFW_PRESS) set_cursor_captured(!captured_);
  InputEvent e;
  e.kind = InputKind::kKey;
  e.key = key;
  e.action = action;
  push(e);
}

void Window::on_cursor(double x, double y) {
  const bool first = !have_cursor_;
  const double dx = x - cursor_x_, dy = y - cursor_y_;
  cursor_x_ = x;
  cursor_y_ = y;
  have_cursor_ = true;
  if (first || (dx == 0 && dy == 0)) return;
  if (!captured_ && !left_down_) return;
  InputEvent e;
  e.kind = InputKind::kMouse;
  e.dx = dx;
  e.dy = dy;
  push(e);
}

void Window::on_button(int button, int action) {
  if (button == GLFW_MOUSE_BUTTON_LEFT)
    left_down_ = action == GLFW_PRESS && (captured_ || !ImGui::GetIO().WantCaptureMouse);
  InputEvent e;
  e.kind = InputKind::kButton;
  e.button = button;
  e.action = action;
  push(e);
}

void Window::on_scroll(double dx, double dy) {
  if (!captured_ && ImGui::GetIO().WantCaptureMouse) return;
  InputEvent e;
  e.kind = InputKind::kWheel;
  e.dx = dx;
  e.dy = dy;
  push(e);
}

}  // namespace terrasprite::viewer
