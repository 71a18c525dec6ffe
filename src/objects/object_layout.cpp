// SPDX-License-Identifier: MIT
// Scene files: models, listed instances, scattered instances on the terrain.
#include "terrasprite/objects/object_layout.h"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <random>

#include "terrasprite/common/error.h"
#include "terrasprite/common/input_file.h"
#include "terrasprite/terrain/grid_mesh.h"

namespace terrasprite {
namespace {

// Heights in metres chosen so the objects read as what they are on a
// terrain: statues (bunny, rocker arm, fandisk, teapot), a car, a cow, a
// truck, and a forest patch ~20 m across. Counts give 2.2 M triangles.
const char* const kDefaultScene = R"({
  "models": [
    {"name": "bunny", "file": "models_scans/stanford-bunny.obj", "up": "y", "height_m": 8, "color": [0.78, 0.74, 0.66]},
    {"name": "beetle", "file": "models_scans/beetle-alt.obj", "up": "y", "height_m": 1.5, "color": [0.55, 0.62, 0.75]},
    {"name": "rocker-arm", "file": "models_scans/rocker-arm.obj", "up": "y", "height_m": 6, "color": [0.70, 0.70, 0.72]},
    {"name": "fandisk", "file": "models_scans/fandisk.obj", "up": "y", "height_m": 5, "color": [0.80, 0.68, 0.50]},
    {"name": "teapot", "file": "models_scans/teapot.obj", "up": "y", "height_m": 4, "color": [0.85, 0.85, 0.80]},
    {"name": "spot", "file": "models_scans/spot.obj", "up": "y", "height_m": 1.6, "texture": "models_scans/spot_texture.png"},
    {"name": "milk-truck", "file": "models_cesium_milk_truck/CesiumMilkTruck.glb", "up": "y", "height_m": 2.9},
    {"name": "forest", "file": "models_kenney_racing/decoration-forest.glb", "up": "y", "height_m": 10}
  ],
  "scatter": [
    {"model": "bunny", "count": 4},
    {"model": "beetle", "count": 5},
    {"model": "rocker-arm", "count": 8},
    {"model": "fandisk", "count": 12},
    {"model": "teapot", "count": 60},
    {"model": "spot", "count": 60},
    {"model": "milk-truck", "count": 101},
    {"model": "forest", "count": 150}
  ],
  "scatter_defaults": {"seed": 7, "region": [-300, -300, 300, 300], "max_slope_deg": 35, "min_spacing_m": 14}
})";

[[noreturn]] void fail(const std::string& name, const std::string& what) {
  throw InputError(fmt::format("{}: {}", name, what));
}

std::string resolve(const std::string& base_dir, const std::string& file) {
  const std::filesystem::path p(file);
  return p.is_absolute() ? file : (std::filesystem::path(base_dir) / p).string();
}

LayoutModel parse_model(const nlohmann::json& m, const std::string& name, const std::string& base) {
  LayoutModel out;
  out.name = m.at("name").get<std::string>();
  out.file = resolve(base, m.at("file").get<std::string>());
  out.options.up = parse_up_axis(m.value("up", std::string("y")),
                                 fmt::format("{}: model '{}': up", name, out.name).c_str());
  out.options.height_m = m.value("height_m", 0.0);
  if (!(out.options.height_m >= 0) || out.options.height_m > 1e4)
    fail(name,
         fmt::format("model '{}': height_m {} is not in 0..10000", out.name, out.options.height_m));
  if (m.contains("texture")) out.options.texture = resolve(base, m["texture"].get<std::string>());
  if (m.contains("color")) {
    const auto c = m["color"].get<std::vector<double>>();
    if (c.size() != 3 && c.size() != 4)
      fail(name, fmt::format("model '{}': color needs 3 or 4 values", out.name));
    out.options.color = glm::vec4(c[0], c[1], c[2], c.size() == 4 ? c[3] : 1.0);
  }
  if (m.contains("double_sided")) {
    if (!m["double_sided"].is_boolean())
      fail(name, fmt::format("model '{}': double_sided must be true or false", out.name));
    out.options.double_sided = m["double_sided"].get<bool>();
  }
  return out;
}

double slope_deg(const Heightfield& h, double x, double y) {
  const double e = std::max(h.spacing_x, h.spacing_y);
  const double dx = (h.sample(x + e, y) - h.sample(x - e, y)) / (2 * e);
  const double dy = (h.sample(x, y + e) - h.sample(x, y - e)) / (2 * e);
  return glm::degrees(std::atan(std::hypot(dx, dy)));
}

struct Scatter {
  int model = 0, count = 0;
  unsigned seed = 1;
  std::array<double, 4> region{};
  double max_slope_deg = 90, min_spacing_m = 0;
};

void scatter(const Scatter& s, const std::string& name, const std::string& model_name,
             const Heightfield& h, const std::function<double(double, double)>& ground,
             std::vector<PlacedInstance>& placed) {
  std::mt19937 rng(s.seed * 2654435761u + unsigned(s.model));
  std::uniform_real_distribution<double> ux(s.region[0], s.region[2]), uy(s.region[1], s.region[3]),
      heading(0, 360);
  int done = 0;
  const long attempts = 200L * s.count + 1000;
  for (long a = 0; a < attempts && done < s.count; ++a) {
    const double x = ux(rng), y = uy(rng), hd = heading(rng);
    if (slope_deg(h, x, y) > s.max_slope_deg) continue;
    bool near = false;
    for (const PlacedInstance& p : placed)
      near = near ||
             std::hypot(p.instance.position.x - x, p.instance.position.y - y) < s.min_spacing_m;
    if (near) continue;
    placed.push_back({s.model, {{x, y, ground(x, y)}, hd, 1.0}});
    ++done;
  }
  if (done < s.count)
    fail(name,
         fmt::format("scatter of '{}': placed only {} of {} instances (region too small, slope "
                     "limit or spacing too strict)",
                     model_name, done, s.count));
}

void check_region(const std::array<double, 4>& r, const Heightfield& h, const std::string& name) {
  const double hx = h.extent_x() / 2, hy = h.extent_y() / 2;
  if (!(r[0] < r[2] && r[1] < r[3]) || r[0] < -hx || r[2] > hx || r[1] < -hy || r[3] > hy)
    fail(name,
         fmt::format(
             "scatter region [{}, {}, {}, {}] is empty or leaves the terrain ({:.0f} x {:.0f} m "
             "centred on 0)",
             r[0], r[1], r[2], r[3], h.extent_x(), h.extent_y()));
}

}  // namespace

const char* default_layout_json() {
  return kDefaultScene;
}

ObjectLayout parse_object_layout(const std::string& text, const std::string& name,
                                 const std::string& base_dir, const Heightfield& h) {
  ObjectLayout scene;
  // Instances stand on the full-resolution triangles the GL renderers draw,
  // not the bilinear surface: the two part by metres inside a 30 m quad,
  // enough to bury a bush or float a truck. A coarser drawn grid grounds
  // them again (ground_instances).
  const auto ground = grid_surface(h, 0);
  try {
    const nlohmann::json j = nlohmann::json::parse(text);
    std::map<std::string, int> index;
    for (const auto& m : j.at("models")) {
      scene.models.push_back(parse_model(m, name, base_dir));
      if (!index.emplace(scene.models.back().name, int(scene.models.size()) - 1).second)
        fail(name, fmt::format("model name '{}' appears twice", scene.models.back().name));
    }
    if (scene.models.empty()) fail(name, "the scene has no models");
    auto model_of = [&](const nlohmann::json& v) {
      auto it = index.find(v.get<std::string>());
      if (it == index.end()) fail(name, fmt::format("unknown model '{}'", v.get<std::string>()));
      return it->second;
    };
    for (const auto& i : j.value("instances", nlohmann::json::array())) {
      const auto p = i.at("position").get<std::vector<double>>();
      if (p.size() != 2 && p.size() != 3)
        fail(name, "an instance position needs [x, y] or [x, y, z]");
      const double z = p.size() == 3 ? p[2] : ground(p[0], p[1]);
      const double scale = i.value("scale", 1.0);
      if (!(scale > 0)) fail(name, "an instance scale must be positive");
      scene.instances.push_back({model_of(i.at("model")),
                                 {{p[0], p[1], z}, i.value("heading_deg", 0.0), scale},
                                 p.size() != 3});
    }
    const nlohmann::json defaults = j.value("scatter_defaults", nlohmann::json::object());
    for (const auto& s : j.value("scatter", nlohmann::json::array())) {
      nlohmann::json merged = defaults;
      merged.update(s);
      Scatter sc;
      sc.model = model_of(merged.at("model"));
      sc.count = merged.at("count").get<int>();
      sc.seed = merged.value("seed", 1u);
      const auto r =
          merged.value("region", std::vector<double>{-h.extent_x() / 2, -h.extent_y() / 2,
                                                     h.extent_x() / 2, h.extent_y() / 2});
      if (r.size() != 4) fail(name, "a scatter region needs [x0, y0, x1, y1]");
      sc.region = {r[0], r[1], r[2], r[3]};
      sc.max_slope_deg = merged.value("max_slope_deg", 90.0);
      sc.min_spacing_m = merged.value("min_spacing_m", 0.0);
      if (sc.count < 0 || sc.count > 1000000)
        fail(name, fmt::format("scatter count {} is not in 0..1000000", sc.count));
      check_region(sc.region, h, name);
      scatter(sc, name, scene.models[sc.model].name, h, ground, scene.instances);
    }
  } catch (const nlohmann::json::exception& e) {
    fail(name, fmt::format("not a valid scene file ({})", e.what()));
  }
  return scene;
}

ObjectLayout load_object_layout(const std::string& path, const Heightfield& heights) {
  const std::string text = read_input_text(path, "scene file");
  return parse_object_layout(text, path, std::filesystem::path(path).parent_path().string(),
                             heights);
}

void ground_instances(ObjectLayout& scene, const std::function<double(double, double)>& ground) {
  for (PlacedInstance& p : scene.instances)
    if (p.grounded) p.instance.position.z = ground(p.instance.position.x, p.instance.position.y);
}

ObjectLayout default_object_layout(const std::string& models_dir, const Heightfield& heights) {
  return parse_object_layout(kDefaultScene, "default scene", models_dir, heights);
}

}  // namespace terrasprite
