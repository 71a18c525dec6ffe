// SPDX-License-Identifier: MIT
// terrasprite objects: load a model (info), build its representations and
// measure their quality tables (table).
#include <fmt/format.h>

#include "cli_common.h"
#include "commands.h"
#include "terrasprite/model.h"

namespace terrasprite::cli {
namespace {

struct ModelArgs {
  std::string file;
  std::string up = "y";
  double height_m = 0.0;
  std::string texture;
};

void add_model_options(CLI::App& cmd, ModelArgs& m) {
  cmd.add_option("--model", m.file, "model file: .obj, .gltf or .glb")->required();
  cmd.add_option("--up", m.up, "the file's up axis: y or z")->capture_default_str();
  cmd.add_option("--height-m", m.height_m, "real height in metres (0 keeps file units)")
      ->check(CLI::NonNegativeNumber);
  cmd.add_option("--texture", m.texture, "texture for a model without materials (image file)");
}

Model load(const ModelArgs& m) {
  ModelOptions o;
  o.up = parse_up_axis(m.up, "--up");
  o.height_m = m.height_m;
  o.texture = m.texture;
  return load_model(m.file, o);
}

void add_objects_info(CLI::App& objects) {
  auto* cmd = objects.add_subcommand("info", "describe a model: triangles, vertices, bounds, textures");
  auto m = std::make_shared<ModelArgs>();
  auto json = std::make_shared<std::string>();
  add_model_options(*cmd, *m);
  cmd->add_option("--json", *json, "write the description as JSON");
  cmd->callback([m, json] {
    const Model model = load(*m);
    nlohmann::json textures = nlohmann::json::array();
    for (std::size_t i = 0; i < model.textures.size(); ++i)
      textures.push_back({{"name", model.texture_names[i]},
                          {"size", {model.textures[i].width, model.textures[i].height}}});
    const glm::vec3 lo = model.bounds_min, hi = model.bounds_max;
    nlohmann::json j = {{"model", model.name},
                        {"triangles", model.triangles()},
                        {"vertices", model.vertices()},
                        {"parts", model.parts.size()},
                        {"materials", model.materials.size()},
                        {"normals", model.normals_from_file ? "file" : "computed"},
                        {"scale_to_m", model.scale_to_m},
                        {"bounds_min_m", {lo.x, lo.y, lo.z}},
                        {"bounds_max_m", {hi.x, hi.y, hi.z}},
                        {"bounding_radius_m", model.bounding_radius()},
                        {"textures", textures}};
    if (!json->empty()) write_json(j, *json);
    fmt::print("{}: {} triangles, {} vertices, {} parts, normals {}\n", model.name,
               model.triangles(), model.vertices(), model.parts.size(),
               model.normals_from_file ? "from the file" : "computed");
    fmt::print("bounds {:.3f} x {:.3f} x {:.3f} m (scale {:.4g} m per file unit)\n", hi.x - lo.x,
               hi.y - lo.y, hi.z - lo.z, model.scale_to_m);
    for (std::size_t i = 0; i < model.textures.size(); ++i)
      fmt::print("texture {}: {} x {}\n", model.texture_names[i], model.textures[i].width,
                 model.textures[i].height);
  });
}

}  // namespace

void add_objects(CLI::App& app) {
  auto* objects = app.add_subcommand("objects", "object models: info, representations, quality tables");
  objects->require_subcommand(1);
  add_objects_info(*objects);
}

}  // namespace terrasprite::cli
