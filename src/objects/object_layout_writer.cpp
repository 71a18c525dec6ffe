// SPDX-License-Identifier: MIT
#include "terrasprite/objects/object_layout_writer.h"

#include <filesystem>
#include <nlohmann/json.hpp>

namespace terrasprite {
namespace {

std::string absolute_path(const std::string& file) {
  std::error_code ec;
  const std::filesystem::path p = std::filesystem::absolute(file, ec);
  return ec ? file : p.lexically_normal().string();
}

nlohmann::json layout_model_json(const LayoutModel& m) {
  nlohmann::json j = {
      {"name", m.name},
      {"file", absolute_path(m.file)},
      {"up", m.options.up == UpAxis::kZ ? "z" : "y"},
      {"height_m", m.options.height_m},
      {"color", {m.options.color.r, m.options.color.g, m.options.color.b, m.options.color.a}}};
  if (!m.options.texture.empty()) j["texture"] = absolute_path(m.options.texture);
  if (m.options.double_sided) j["double_sided"] = *m.options.double_sided;
  return j;
}

}  // namespace

std::string object_layout_json(const ObjectLayout& layout) {
  nlohmann::json models = nlohmann::json::array(), instances = nlohmann::json::array();
  for (const LayoutModel& m : layout.models) models.push_back(layout_model_json(m));
  for (const PlacedInstance& p : layout.instances) {
    const ObjectInstance& i = p.instance;
    instances.push_back({{"model", layout.models[std::size_t(p.model)].name},
                         {"position", {i.position.x, i.position.y, i.position.z}},
                         {"heading_deg", i.heading_deg},
                         {"scale", i.scale}});
  }
  return nlohmann::json{{"models", models}, {"instances", instances}}.dump(1) + "\n";
}

}  // namespace terrasprite
