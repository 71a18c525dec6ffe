// SPDX-License-Identifier: MIT
// The viewer's input layer: events as GLFW's callbacks deliver them, from a
// window or from a timed script (`view --script FILE`), one path for both.
#pragma once
#include <string>
#include <string_view>
#include <vector>

namespace terrasprite::viewer {

enum class InputKind { kKey, kMouse, kButton, kWheel, kScreenshot };

/// One input event. Keys and buttons use GLFW's codes (GLFW_KEY_*,
/// GLFW_MOUSE_BUTTON_*) and actions (0 release, 1 press, 2 repeat).
struct InputEvent {
  InputKind kind = InputKind::kKey;
  int key = -1;           ///< kKey
  int action = 1;         ///< kKey, kButton
  int button = 0;         ///< kButton
  double dx = 0, dy = 0;  ///< kMouse: cursor motion in pixels; kWheel: scroll offset
  std::string file;       ///< kScreenshot: PNG to write
};

/// An event of a script, due `t` seconds after the run starts.
struct ScriptEvent {
  double t = 0;
  InputEvent event;
};

/// Reads a script: {"events": [{"t": 0.5, "type": "key", "key": "W", "action":
/// "press"}, {"t": 2.5, "type": "mouse", "dx": 40, "dy": 0}, {"t": 3, "type":
/// "screenshot", "file": "a.png"}, {"type": "button", "button": "left",
/// "action": "press"}, {"type": "wheel", "dy": 1}]}. Keys: A-Z, 0-9, UP, DOWN,
/// LEFT, RIGHT, SPACE, SHIFT, CTRL, ESCAPE, F1-F12 (also TAB, PLUS, MINUS).
/// Events come back sorted by t (stable). Screenshot files are relative to the
/// working directory. Numbers are bounded: t in [0, 86400] s, mouse dx, dy
/// within +-100000 px, wheel dx, dy within +-100. Throws InputError naming
/// the file, the event's line and index for a missing or malformed file.
std::vector<ScriptEvent> load_input_script(const std::string& file);

/// load_input_script of a script's text; `file` names it in messages.
std::vector<ScriptEvent> parse_input_script(std::string_view text, const std::string& file);

/// GLFW key code of a script key name, or -1.
int key_code(const std::string& name);

}  // namespace terrasprite::viewer
