// SPDX-License-Identifier: MIT
#include "viewer/panel.h"

#include <imgui.h>

#include <algorithm>
#include <array>

namespace terrasprite::viewer {

namespace {

constexpr std::array kWarps = {"none", "poly2", "depth"};

// Bars of frame time, keyframes in orange, with the 33 ms (30 fps) and 100 ms lines.
void frame_graph(const std::deque<GraphSample>& history) {
  const ImVec2 size(320, 70);
  const ImVec2 p = ImGui::GetCursorScreenPos();
  ImDrawList* dl = ImGui::GetWindowDrawList();
  dl->AddRectFilled(p, ImVec2(p.x + size.x, p.y + size.y), IM_COL32(20, 20, 20, 200));
  float top_ms = 150.f;  // grows to the slowest frame shown, up to 2 s
  for (const GraphSample& s : history) top_ms = std::max(top_ms, std::min(s.ms * 1.1f, 2000.f));
  auto y_of = [&](float ms) { return p.y + size.y * (1.f - std::min(ms, top_ms) / top_ms); };
  const float bar = size.x / 240.f;
  float x = p.x + size.x - bar * float(history.size());
  for (const GraphSample& s : history) {
    dl->AddRectFilled(ImVec2(x, y_of(s.ms)), ImVec2(x + std::max(bar, 1.f), p.y + size.y),
                      s.key ? IM_COL32(255, 150, 40, 255) : IM_COL32(90, 200, 110, 255));
    x += bar;
  }
  for (float ms : {33.3f, 100.f})
    dl->AddLine(ImVec2(p.x, y_of(ms)), ImVec2(p.x + size.x, y_of(ms)),
                IM_COL32(200, 200, 200, 120));
  ImGui::Dummy(size);
  ImGui::TextDisabled("frame ms, top %.0f (lines: 33, 100; orange: keyframe)", top_ms);
}

}  // namespace

PanelActions draw_panel(const PanelInfo& info, LiveSettings& settings) {
  PanelActions act;
  ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowBgAlpha(0.7f);
  ImGui::Begin("terrasprite", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
  ImGui::Text("%.1f fps   render %.1f ms   %s", info.fps, info.render_ms, info.cls.c_str());
  ImGui::Text("%lld triangles", info.triangles);
  if (info.building)
    ImGui::TextColored(ImVec4(1, .8f, .3f, 1), "building the %s renderer...",
                       to_string(settings.mode));
  else if (info.stale_ms > 100)
    ImGui::TextColored(ImVec4(1, .8f, .3f, 1), "rendering: showing the last frame (%.0f ms old)",
                       info.stale_ms);
  frame_graph(info.history);
  std::array<const char*, kRenderModes.size()> names;
  for (std::size_t i = 0; i < names.size(); ++i) names[i] = to_string(kRenderModes[i]);
  int mode = int(std::find(kRenderModes.begin(), kRenderModes.end(), settings.mode) -
                 kRenderModes.begin());
  if (ImGui::Combo("mode (1-4)", &mode, names.data(), int(names.size())))
    settings.mode = kRenderModes[std::size_t(mode)];
  if (settings.mode == RenderMode::kSprite) {
    ImGui::Text("sprite error %.2f px", info.error_px);
    if (const auto& k = info.keyframes) {
      // The second thread's keyframes: how many, how late, what each costs there.
      ImGui::Text("keyframes %lld landed of %lld asked (%lld late)%s", k->landed, k->requested,
                  k->late, k->in_flight ? ", one rendering" : "");
      ImGui::Text("last keyframe %.0f ms on the worker, landed after %.0f frames (mean %.1f)",
                  k->last_keyframe_ms, k->last_latency_frames, k->mean_latency_frames);
      if (k->in_flight)  // until it lands, frames show the coarse mesh or an older sprite
        ImGui::TextColored(ImVec4(1, .8f, .3f, 1),
                           k->landed == 0 ? "keyframe pending: showing the coarse LOD mesh"
                                          : "keyframe pending: showing the last one warped");
    }
    float th = float(settings.threshold_px);
    if (ImGui::SliderFloat("threshold px", &th, 0.25f, 8.f, "%.2f", ImGuiSliderFlags_Logarithmic))
      settings.threshold_px = th;
  }
  if (settings.mode == RenderMode::kSprite || settings.mode == RenderMode::kLod)
    ImGui::SliderInt("coarse quads", &settings.lod_quads, 4, 128);
  if (settings.mode == RenderMode::kVoxel) {
    float ratio = float(settings.voxel_ratio);
    if (ImGui::SliderFloat("pixel/voxel ratio", &ratio, 0.5f, 8.f, "%.2f",
                           ImGuiSliderFlags_Logarithmic))
      settings.voxel_ratio = ratio;
    int warp = int(std::find(kWarps.begin(), kWarps.end(), settings.warp) - kWarps.begin());
    if (ImGui::Combo("warp", &warp, kWarps.data(), int(kWarps.size())))
      settings.warp = kWarps[std::size_t(warp)];
    if (settings.warp != "none") ImGui::SliderInt("real frame every", &settings.real_every, 2, 8);
  }
  act.compare = ImGui::Button(info.comparing ? "comparing..." : "compare with full (F3)");
  if (info.compared) {
    ImGui::SameLine();
    act.toggle_difference =
        ImGui::Button(info.show_difference ? "show frames" : "show difference (F4)");
    ImGui::Text("%s vs full: PSNR %.2f dB  SSIM %.4f  FLIP %.4f", to_string(info.compared_mode),
                info.psnr, info.ssim, info.flip);
  }
  ImGui::Separator();
  const auto& c = info.camera;
  ImGui::Text("eye %.0f %.0f %.0f m  yaw %.0f  pitch %.0f", c.position.x, c.position.y,
              c.position.z, c.yaw_deg, c.pitch_deg);
  ImGui::Text("speed %.0f m/s (wheel, +/-)  clearance %.0f m", info.speed_mps, info.clearance_m);
  ImGui::Text("%s%s%s", info.orbit ? "orbit  " : "fly  ", info.recording ? "REC  " : "",
              info.playing ? "playing path" : "");
  act.screenshot = ImGui::Button("screenshot (F2)");
  ImGui::SameLine();
  act.toggle_record = ImGui::Button(info.recording ? "stop recording (F5)" : "record (F5)");
  ImGui::SameLine();
  act.play = ImGui::Button("play (F6)");
  if (!info.message.empty()) ImGui::TextWrapped("%s", info.message.c_str());
  ImGui::TextDisabled("%s  |  F1 keys  |  TAB %s mouse", info.device.c_str(),
                      info.captured ? "frees" : "captures");
  ImGui::End();
  return act;
}

void draw_help() {
  ImGui::SetNextWindowPos(ImVec2(360, 8), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowBgAlpha(0.8f);
  ImGui::Begin("keys (F1)", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
  static const char* lines[] = {
      "W / S, UP / DOWN   forward / back",
      "A / D              strafe left / right",
      "LEFT / RIGHT       turn",
      "Q / E              up / down",
      "mouse              look (TAB frees the cursor; then drag with the left button)",
      "wheel, + / -       speed x / / 1.25",
      "SHIFT              fast (x4)",
      "O                  orbit the ground point at the centre (again: fly)",
      "R                  reset the view",
      "1 2 3 4            mode full / lod / sprite / voxel",
      "F2                 screenshot (PNG)",
      "F3                 compare this view with full resolution",
      "F4                 show the difference image / the frames",
      "F5                 record the flight (path JSON)",
      "F6                 play the recorded path",
      "ESCAPE             quit"};
  for (const char* l : lines) ImGui::TextUnformatted(l);
  ImGui::End();
}

}  // namespace terrasprite::viewer
