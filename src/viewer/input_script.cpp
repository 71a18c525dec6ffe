// SPDX-License-Identifier: MIT
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <fmt/format.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "terrasprite/common/error.h"
#include "terrasprite/common/input_file.h"
#include "viewer/input_event.h"

namespace terrasprite::viewer {

int key_code(const std::string& name) {
  if (name.size() == 1 && name[0] >= 'A' && name[0] <= 'Z') return GLFW_KEY_A + (name[0] - 'A');
  if (name.size() == 1 && name[0] >= '0' && name[0] <= '9') return GLFW_KEY_0 + (name[0] - '0');
  if (name.size() >= 2 && name[0] == 'F') {
    int n = 0;
    if (std::sscanf(name.c_str() + 1, "%d", &n) == 1 && n >= 1 && n <= 12 &&
        name == fmt::format("F{}", n))
      return GLFW_KEY_F1 + n - 1;
  }
  static const std::pair<const char*, int> named[] = {{"UP", GLFW_KEY_UP},
                                                      {"DOWN", GLFW_KEY_DOWN},
                                                      {"LEFT", GLFW_KEY_LEFT},
                                                      {"RIGHT", GLFW_KEY_RIGHT},
                                                      {"SPACE", GLFW_KEY_SPACE},
                                                      {"SHIFT", GLFW_KEY_LEFT_SHIFT},
                                                      {"CTRL", GLFW_KEY_LEFT_CONTROL},
                                                      {"ESCAPE", GLFW_KEY_ESCAPE},
                                                      {"TAB", GLFW_KEY_TAB},
                                                      {"PLUS", GLFW_KEY_EQUAL},
                                                      {"MINUS", GLFW_KEY_MINUS}};
  for (const auto& [n, code] : named)
    if (name == n) return code;
  return -1;
}

namespace {

int parse_action(const nlohmann::json& e, const std::string& where) {
  const std::string a = e.value("action", "");
  if (a == "press") return GLFW_PRESS;
  if (a == "release") return GLFW_RELEASE;
  throw InputError(fmt::format("{}: \"action\" must be \"press\" or \"release\"", where));
}

double number(const nlohmann::json& e, const char* key, const std::string& where, double dflt) {
  if (!e.contains(key)) return dflt;
  if (!e[key].is_number()) throw InputError(fmt::format("{}: \"{}\" must be a number", where, key));
  return e[key].get<double>();
}

InputEvent parse_event(const nlohmann::json& e, const std::string& where) {
  InputEvent ev;
  const std::string type = e.contains("type") && e["type"].is_string() ? e["type"] : "";
  if (type == "key") {
    ev.kind = InputKind::kKey;
    const std::string k = e.contains("key") && e["key"].is_string() ? e["key"] : "";
    ev.key = key_code(k);
    if (ev.key < 0) throw InputError(fmt::format("{}: unknown key \"{}\"", where, k));
    ev.action = parse_action(e, where);
  } else if (type == "mouse") {
    ev.kind = InputKind::kMouse;
    ev.dx = number(e, "dx", where, 0);
    ev.dy = number(e, "dy", where, 0);
  } else if (type == "button") {
    ev.kind = InputKind::kButton;
    const std::string b = e.value("button", "left");
    ev.button = b == "left"     ? GLFW_MOUSE_BUTTON_LEFT
                : b == "right"  ? GLFW_MOUSE_BUTTON_RIGHT
                : b == "middle" ? GLFW_MOUSE_BUTTON_MIDDLE
                                : -1;
    if (ev.button < 0) throw InputError(fmt::format("{}: unknown button \"{}\"", where, b));
    ev.action = parse_action(e, where);
  } else if (type == "wheel") {
    ev.kind = InputKind::kWheel;
    ev.dx = number(e, "dx", where, 0);
    ev.dy = number(e, "dy", where, 0);
  } else if (type == "screenshot") {
    ev.kind = InputKind::kScreenshot;
    const std::string f = e.contains("file") && e["file"].is_string() ? e["file"] : "";
    if (f.empty()) throw InputError(fmt::format("{}: screenshot needs a \"file\"", where));
    ev.file = f;
  } else {
    throw InputError(
        fmt::format("{}: \"type\" must be key, mouse, button, wheel or screenshot", where));
  }
  return ev;
}

}  // namespace

std::vector<ScriptEvent> load_input_script(const std::string& file) {
  nlohmann::json j = nlohmann::json::parse(read_input_text(file, "script file"), nullptr, false);
  if (j.is_discarded() || !j.is_object())
    throw InputError(fmt::format("{}: not a JSON object (expected {{\"events\": [...]}})", file));
  if (!j.contains("events") || !j["events"].is_array())
    throw InputError(fmt::format("{}: \"events\" must be an array", file));
  std::vector<ScriptEvent> out;
  for (std::size_t i = 0; i < j["events"].size(); ++i) {
    const auto& e = j["events"][i];
    const std::string where = fmt::format("{}: event {}", file, i);
    if (!e.is_object()) throw InputError(fmt::format("{}: must be an object", where));
    const double t = number(e, "t", where, 0);
    if (!(t >= 0 && t <= 86400))
      throw InputError(fmt::format("{}: \"t\" must be between 0 and 86400 seconds", where));
    out.push_back({t, parse_event(e, where)});
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const ScriptEvent& a, const ScriptEvent& b) { return a.t < b.t; });
  return out;
}

}  // namespace terrasprite::viewer
