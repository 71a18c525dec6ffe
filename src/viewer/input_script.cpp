// SPDX-License-Identifier: MIT
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <fmt/format.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <string_view>

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

/// A string from the script as a message quotes it: at most 60 characters.
std::string shown(const std::string& text) {
  return text.size() <= 60 ? text : text.substr(0, 57) + "...";
}

/// The event's string `key`; `dflt` when absent; "" (refused by the caller)
/// when it is not a string.
std::string string_or(const nlohmann::json& e, const char* key, const char* dflt) {
  if (!e.contains(key)) return dflt;
  return e[key].is_string() ? e[key].get<std::string>() : std::string();
}

int parse_action(const nlohmann::json& e, const std::string& where) {
  const std::string a = string_or(e, "action", "");
  if (a == "press") return GLFW_PRESS;
  if (a == "release") return GLFW_RELEASE;
  throw InputError(fmt::format("{}: \"action\" must be \"press\" or \"release\"", where));
}

// Bounds of script numbers: cursor motion per event (pixels), wheel offset
// per event (notches), event times (seconds, a day).
constexpr double kMaxMousePx = 100000, kMaxWheel = 100, kMaxScriptS = 86400;

/// A number of the event in [lo, hi] (`dflt` when absent).
double number(const nlohmann::json& e, const char* key, const std::string& where, double dflt,
              double lo, double hi) {
  if (!e.contains(key)) return dflt;
  if (!e[key].is_number()) throw InputError(fmt::format("{}: \"{}\" must be a number", where, key));
  const double v = e[key].get<double>();
  if (!(v >= lo && v <= hi))
    throw InputError(
        fmt::format("{}: \"{}\" {:g} must be between {:g} and {:g}", where, key, v, lo, hi));
  return v;
}

/// The line (1-based) where each element of the top-level "events" array
/// begins in `text`, a valid JSON document: messages name FILE:LINE.
std::vector<int> event_lines(std::string_view text) {
  std::vector<int> lines;
  int line = 1, depth = 0, events_depth = -1;
  bool in_string = false, escaped = false, expect_element = false;
  std::size_t string_start = 0;
  std::string_view last_string, key;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (escaped) {
        escaped = false;
      } else if (c == '\\') {
        escaped = true;
      } else if (c == '"') {
        in_string = false;
        if (depth == 1) last_string = text.substr(string_start, i - string_start);
      }
      continue;
    }
    if (c == '\n') ++line;
    if (c == ' ' || c == '\t' || c == '\n' || c == '\r') continue;
    if (expect_element && depth == events_depth) {
      if (c != ']') lines.push_back(line);
      expect_element = false;
    }
    if (c == '"') {
      in_string = true;
      string_start = i + 1;
    } else if (c == '{' || c == '[') {
      if (c == '[' && depth == 1 && key == "events") {
        events_depth = 2;
        lines.clear();  // a repeated key: the last one counts, as for the parser
        expect_element = true;
      }
      ++depth;
    } else if (c == '}' || c == ']') {
      if (depth == events_depth) events_depth = -1;
      --depth;
    } else if (c == ',' && depth == events_depth) {
      expect_element = true;
    } else if (c == ':' && depth == 1) {
      key = last_string;
    }
  }
  return lines;
}

InputEvent parse_event(const nlohmann::json& e, const std::string& where) {
  InputEvent ev;
  const std::string type = e.contains("type") && e["type"].is_string() ? e["type"] : "";
  if (type == "key") {
    ev.kind = InputKind::kKey;
    const std::string k = e.contains("key") && e["key"].is_string() ? e["key"] : "";
    ev.key = key_code(k);
    if (ev.key < 0) throw InputError(fmt::format("{}: unknown key \"{}\"", where, shown(k)));
    ev.action = parse_action(e, where);
  } else if (type == "mouse") {
    ev.kind = InputKind::kMouse;
    ev.dx = number(e, "dx", where, 0, -kMaxMousePx, kMaxMousePx);
    ev.dy = number(e, "dy", where, 0, -kMaxMousePx, kMaxMousePx);
  } else if (type == "button") {
    ev.kind = InputKind::kButton;
    const std::string b = string_or(e, "button", "left");
    ev.button = b == "left"     ? GLFW_MOUSE_BUTTON_LEFT
                : b == "right"  ? GLFW_MOUSE_BUTTON_RIGHT
                : b == "middle" ? GLFW_MOUSE_BUTTON_MIDDLE
                                : -1;
    if (ev.button < 0) throw InputError(fmt::format("{}: unknown button \"{}\"", where, shown(b)));
    ev.action = parse_action(e, where);
  } else if (type == "wheel") {
    ev.kind = InputKind::kWheel;
    ev.dx = number(e, "dx", where, 0, -kMaxWheel, kMaxWheel);
    ev.dy = number(e, "dy", where, 0, -kMaxWheel, kMaxWheel);
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

std::vector<ScriptEvent> parse_input_script(std::string_view text, const std::string& file) {
  nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  if (j.is_discarded() || !j.is_object())
    throw InputError(fmt::format("{}: not a JSON object (expected {{\"events\": [...]}})", file));
  if (!j.contains("events") || !j["events"].is_array())
    throw InputError(fmt::format("{}: \"events\" must be an array", file));
  const std::vector<int> lines = event_lines(text);
  std::vector<ScriptEvent> out;
  for (std::size_t i = 0; i < j["events"].size(); ++i) {
    const auto& e = j["events"][i];
    const std::string where = lines.size() == j["events"].size()
                                  ? fmt::format("{}:{}: event {}", file, lines[i], i)
                                  : fmt::format("{}: event {}", file, i);
    if (!e.is_object()) throw InputError(fmt::format("{}: must be an object", where));
    const double t = number(e, "t", where, 0, 0, kMaxScriptS);
    out.push_back({t, parse_event(e, where)});
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const ScriptEvent& a, const ScriptEvent& b) { return a.t < b.t; });
  return out;
}

std::vector<ScriptEvent> load_input_script(const std::string& file) {
  return parse_input_script(read_input_text(file, "script file"), file);
}

}  // namespace terrasprite::viewer
