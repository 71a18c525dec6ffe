// SPDX-License-Identifier: MIT
// Scene files: models, listed instances, scattered instances on the terrain.
#include "terrasprite/objects/object_layout.h"

#include <fmt/format.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <utility>

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

// The largest scene: instances in all (listed and scattered), models, scatter entries.
constexpr long long kMaxInstances = 1000000;
constexpr std::size_t kMaxModels = 1000, kMaxScatters = 1000;
// Instance scales and model heights.
constexpr double kMinScale = 0.001, kMaxScale = 1000, kMaxHeightM = 10000;

[[noreturn]] void fail(const std::string& name, const std::string& what) {
  throw InputError(fmt::format("{}: {}", name, what));
}

/// A name from the file as a message quotes it: at most 60 characters, so a
/// megabyte-long name never makes a megabyte-long message.
std::string shown(const std::string& text) {
  return text.size() <= 60 ? text : text.substr(0, 57) + "...";
}

/// One JSON object of a scene file: `file` is the scene's name, `path` the
/// object's place in it ("instances[3]"), so every message names the field.
struct Where {
  const std::string& file;
  std::string path;

  std::string field(const char* key) const { return path.empty() ? key : path + "." + key; }
  /// Throws "<file>: <path>.<key><what>".
  [[noreturn]] void fail(const char* key, const std::string& what) const {
    throw InputError(fmt::format("{}: {}{}", file, field(key), what));
  }
};

const nlohmann::json* member(const nlohmann::json& o, const char* key) {
  const auto it = o.find(key);
  return it == o.end() ? nullptr : &*it;
}

/// A number in [lo, hi] (`dflt` when absent).
double number_in(const nlohmann::json& o, const char* key, const Where& w, double dflt, double lo,
                 double hi) {
  const nlohmann::json* v = member(o, key);
  if (!v) return dflt;
  if (!v->is_number()) w.fail(key, ": must be a number");
  const double x = v->get<double>();
  if (!(x >= lo && x <= hi)) w.fail(key, fmt::format(" {:g}: must be in [{:g}, {:g}]", x, lo, hi));
  return x;
}

/// A whole number in lo..hi (`dflt` when absent), read as a double so a value
/// past any integer type is named as written, never wrapped.
long long whole_in(const nlohmann::json& o, const char* key, const Where& w, long long dflt,
                   long long lo, long long hi) {
  const nlohmann::json* v = member(o, key);
  if (!v) return dflt;
  if (!v->is_number()) w.fail(key, ": must be a number");
  const double x = v->get<double>();
  if (!(x >= double(lo) && x <= double(hi)) || x != std::floor(x))
    w.fail(key, fmt::format(" {}: must be a whole number in {}..{}", x, lo, hi));
  return static_cast<long long>(x);
}

std::string string_of(const nlohmann::json& o, const char* key, const Where& w, bool required) {
  const nlohmann::json* v = member(o, key);
  if (!v) {
    if (required) w.fail(key, ": missing");
    return {};
  }
  if (!v->is_string() || v->get<std::string>().empty()) w.fail(key, ": must be a non-empty string");
  return v->get<std::string>();
}

/// An array of numbers of one of the sizes `n1`, `n2`.
std::vector<double> numbers_of(const nlohmann::json& v, const char* key, const Where& w,
                               std::size_t n1, std::size_t n2, const char* shape) {
  if (!v.is_array() || (v.size() != n1 && v.size() != n2))
    w.fail(key, fmt::format(": must be {}", shape));
  std::vector<double> out;
  for (const auto& x : v) {
    if (!x.is_number()) w.fail(key, fmt::format(": must be {} (numbers)", shape));
    out.push_back(x.get<double>());
  }
  return out;
}

std::string resolve(const std::string& base_dir, const std::string& file) {
  const std::filesystem::path p(file);
  return p.is_absolute() ? file : (std::filesystem::path(base_dir) / p).string();
}

LayoutModel parse_model(const nlohmann::json& m, const Where& w, const std::string& base) {
  if (!m.is_object()) throw InputError(fmt::format("{}: {}: must be an object", w.file, w.path));
  LayoutModel out;
  out.name = string_of(m, "name", w, true);
  out.file = resolve(base, string_of(m, "file", w, true));
  const std::string up = m.contains("up") ? string_of(m, "up", w, true) : "y";
  out.options.up = parse_up_axis(
      shown(up), (w.file + ": " + w.field("up") + " (model " + shown(out.name) + ")").c_str());
  out.options.height_m = number_in(m, "height_m", w, 0.0, 0.0, kMaxHeightM);
  if (m.contains("texture")) out.options.texture = resolve(base, string_of(m, "texture", w, true));
  if (m.contains("color")) {
    const auto c = numbers_of(m["color"], "color", w, 3, 4, "[r, g, b] or [r, g, b, a]");
    for (const double v : c)
      if (!(v >= 0 && v <= 1)) w.fail("color", fmt::format(" value {:g}: must be in [0, 1]", v));
    out.options.color = glm::vec4(c[0], c[1], c[2], c.size() == 4 ? c[3] : 1.0);
  }
  if (m.contains("double_sided")) {
    if (!m["double_sided"].is_boolean()) w.fail("double_sided", ": must be true or false");
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
  int model = 0;
  long long count = 0;
  unsigned seed = 1;
  std::array<double, 4> region{};
  double max_slope_deg = 90, min_spacing_m = 0;
};

/// The instances placed so far near a scatter's region (grown by the minimum
/// spacing), bucketed in square cells at least that spacing wide: the
/// spacing test looks at the 3 x 3 cells around a candidate only, and finds
/// exactly the instances a test against every one of them would.
class SpacingGrid {
 public:
  SpacingGrid(const std::array<double, 4>& region, double spacing, long long count)
      : spacing_(spacing) {
    if (!(spacing > 0)) return;
    const double grow = spacing * 1.001;  // cells a little wider than the spacing: rounding
    x0_ = region[0] - grow;
    y0_ = region[1] - grow;
    const double w = region[2] - region[0] + 2 * grow, h = region[3] - region[1] + 2 * grow;
    const double max_cells = 4.0 * double(count) + 1024;
    cell_ = std::max({grow, std::sqrt(w * h / max_cells), w / max_cells, h / max_cells});
    nx_ = int(std::ceil(w / cell_)) + 1;
    ny_ = int(std::ceil(h / cell_)) + 1;
    head_.assign(std::size_t(nx_) * std::size_t(ny_), -1);
  }

  void add(const glm::dvec2& p) {
    if (!(spacing_ > 0)) return;
    const int cx = cell_x(p.x), cy = cell_y(p.y);
    if (cx < 0 || cy < 0 || cx >= nx_ || cy >= ny_) return;  // too far to matter
    points_.push_back(p);
    next_.push_back(std::exchange(head_[std::size_t(cy) * nx_ + cx], int(points_.size()) - 1));
  }

  /// Whether an instance lies closer than the spacing to (x, y), a point of the region.
  bool near(double x, double y) const {
    if (!(spacing_ > 0)) return false;
    const int cx = cell_x(x), cy = cell_y(y);
    for (int j = std::max(0, cy - 1); j <= std::min(ny_ - 1, cy + 1); ++j)
      for (int i = std::max(0, cx - 1); i <= std::min(nx_ - 1, cx + 1); ++i)
        for (int k = head_[std::size_t(j) * nx_ + i]; k >= 0; k = next_[k])
          if (std::hypot(points_[k].x - x, points_[k].y - y) < spacing_) return true;
    return false;
  }

 private:
  int cell_x(double x) const { return int(std::floor((x - x0_) / cell_)); }
  int cell_y(double y) const { return int(std::floor((y - y0_) / cell_)); }

  double spacing_, x0_ = 0, y0_ = 0, cell_ = 1;
  int nx_ = 0, ny_ = 0;
  std::vector<int> head_, next_;
  std::vector<glm::dvec2> points_;
};

// Attempts between checks of a scatter's progress.
constexpr long long kWindow = 65536;

/// Whether a scatter that placed `recent` instances in its last kWindow
/// attempts cannot place the `left` ones in its `attempts_left` even at 16
/// times that rate. The chance of placing an instance only falls as instances
/// fill the region, so such a scatter would fail anyway, only after all its
/// attempts (200 per instance: 2e8 for a million).
bool hopeless(long long recent, long long left, long long attempts_left) {
  return 16.0 * double(recent + 1) / double(kWindow) * double(attempts_left) < double(left);
}

void scatter(const Scatter& s, const Where& w, const std::string& model_name, const Heightfield& h,
             const std::function<double(double, double)>& ground,
             std::vector<PlacedInstance>& placed) {
  std::mt19937 rng(s.seed * 2654435761u + unsigned(s.model));
  std::uniform_real_distribution<double> ux(s.region[0], s.region[2]), uy(s.region[1], s.region[3]),
      heading(0, 360);
  SpacingGrid grid(s.region, s.min_spacing_m, s.count);
  for (const PlacedInstance& p : placed) grid.add(glm::dvec2(p.instance.position));
  long long done = 0, done_before = 0;  // placed, and placed a window ago
  const long long attempts = 200LL * s.count + 1000;
  for (long long a = 0; a < attempts && done < s.count; ++a) {
    if (a > 0 && a % kWindow == 0) {
      if (hopeless(done - done_before, s.count - done, attempts - a)) break;
      done_before = done;
    }
    const double x = ux(rng), y = uy(rng), hd = heading(rng);
    if (slope_deg(h, x, y) > s.max_slope_deg) continue;
    if (grid.near(x, y)) continue;
    placed.push_back({s.model, {{x, y, ground(x, y)}, hd, 1.0}});
    grid.add({x, y});
    ++done;
  }
  if (done < s.count)
    throw InputError(fmt::format(
        "{}: {} of '{}': placed only {} of {} instances (region too small, slope limit or "
        "spacing too strict)",
        w.file, w.path, shown(model_name), done, s.count));
}

void check_region(const std::array<double, 4>& r, const Heightfield& h, const Where& w) {
  const double hx = h.extent_x() / 2, hy = h.extent_y() / 2;
  if (!(r[0] < r[2] && r[1] < r[3]) || r[0] < -hx || r[2] > hx || r[1] < -hy || r[3] > hy)
    w.fail("region", fmt::format(" [{:g}, {:g}, {:g}, {:g}]: empty or leaves the terrain ({:.0f} x "
                                 "{:.0f} m centred on 0)",
                                 r[0], r[1], r[2], r[3], h.extent_x(), h.extent_y()));
}

/// Where listed instances may stand: over the terrain and a margin of half
/// its size on every side; heights within its extent of its height range.
struct InstanceBounds {
  double x, y, z_lo, z_hi;
  explicit InstanceBounds(const Heightfield& h)
      : x(std::max(1.0, h.extent_x())),
        y(std::max(1.0, h.extent_y())),
        z_lo(double(h.min_height()) - std::max(1.0, h.extent())),
        z_hi(double(h.max_height()) + std::max(1.0, h.extent())) {}
};

PlacedInstance parse_instance(
    const nlohmann::json& i, const Where& w, const InstanceBounds& b,
    const std::function<int(const nlohmann::json&, const Where&)>& model_of,
    const std::function<double(double, double)>& ground) {
  if (!i.is_object()) throw InputError(fmt::format("{}: {}: must be an object", w.file, w.path));
  if (!i.contains("position")) w.fail("position", ": missing");
  const auto p = numbers_of(i["position"], "position", w, 2, 3, "[x, y] or [x, y, z]");
  if (!(std::abs(p[0]) <= b.x && std::abs(p[1]) <= b.y))
    w.fail("position",
           fmt::format(" [{:g}, {:g}]: x and y must be within [-{:g}, {:g}] x [-{:g}, {:g}] m "
                       "(the terrain and half its size around it)",
                       p[0], p[1], b.x, b.x, b.y, b.y));
  if (p.size() == 3 && !(p[2] >= b.z_lo && p[2] <= b.z_hi))
    w.fail("position", fmt::format(" z {:g}: must be within [{:g}, {:g}] m (the terrain's heights "
                                   "and its extent below and above them)",
                                   p[2], b.z_lo, b.z_hi));
  const double z = p.size() == 3 ? p[2] : ground(p[0], p[1]);
  const double scale = number_in(i, "scale", w, 1.0, kMinScale, kMaxScale);
  // Any finite heading is a compass direction: reduced into [0, 360).
  const double heading = number_in(i, "heading_deg", w, 0.0, -DBL_MAX, DBL_MAX);
  double hd = std::fmod(heading, 360.0);
  if (hd < 0) hd += 360.0;
  if (hd >= 360.0) hd = 0.0;
  if (!i.contains("model")) w.fail("model", ": missing");
  return {model_of(i["model"], w), {{p[0], p[1], z}, hd, scale}, p.size() != 3};
}

Scatter parse_scatter(const nlohmann::json& merged, const Where& w, const Heightfield& h,
                      const std::function<int(const nlohmann::json&, const Where&)>& model_of) {
  Scatter sc;
  if (!merged.contains("model")) w.fail("model", ": missing");
  sc.model = model_of(merged["model"], w);
  if (!merged.contains("count")) w.fail("count", ": missing");
  sc.count = whole_in(merged, "count", w, 0, 0, kMaxInstances);
  sc.seed = unsigned(whole_in(merged, "seed", w, 1, 0, 4294967295LL));
  if (merged.contains("region")) {
    const auto r = numbers_of(merged["region"], "region", w, 4, 4, "[x0, y0, x1, y1]");
    sc.region = {r[0], r[1], r[2], r[3]};
  } else {
    sc.region = {-h.extent_x() / 2, -h.extent_y() / 2, h.extent_x() / 2, h.extent_y() / 2};
  }
  check_region(sc.region, h, w);
  sc.max_slope_deg = number_in(merged, "max_slope_deg", w, 90.0, 0.0, 90.0);
  sc.min_spacing_m = number_in(merged, "min_spacing_m", w, 0.0, 0.0, std::max(1.0, h.extent()));
  return sc;
}

const nlohmann::json& array_of(const nlohmann::json& j, const char* key, const std::string& name,
                               std::size_t max) {
  static const nlohmann::json empty = nlohmann::json::array();
  if (!j.contains(key)) return empty;
  const nlohmann::json& a = j[key];
  if (!a.is_array()) fail(name, fmt::format("{}: must be an array", key));
  if (a.size() > max)
    fail(name, fmt::format("{}: {} entries, at most {} are allowed", key, a.size(), max));
  return a;
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
    if (!j.is_object()) fail(name, "not a scene file (expected a JSON object with \"models\")");
    if (!j.contains("models")) fail(name, "models: missing");
    std::map<std::string, int> index;
    const nlohmann::json& models = array_of(j, "models", name, kMaxModels);
    for (std::size_t m = 0; m < models.size(); ++m) {
      scene.models.push_back(
          parse_model(models[m], {name, fmt::format("models[{}]", m)}, base_dir));
      if (!index.emplace(scene.models.back().name, int(scene.models.size()) - 1).second)
        fail(name, fmt::format("models[{}].name '{}': appears twice", m,
                               shown(scene.models.back().name)));
    }
    if (scene.models.empty()) fail(name, "the scene has no models");
    const auto model_of = [&](const nlohmann::json& v, const Where& w) {
      if (!v.is_string()) w.fail("model", ": must be a model's name");
      const auto it = index.find(v.get<std::string>());
      if (it == index.end())
        w.fail("model",
               fmt::format(" '{}': no such model in \"models\"", shown(v.get<std::string>())));
      return it->second;
    };
    const InstanceBounds bounds(h);
    const nlohmann::json& listed = array_of(j, "instances", name, std::size_t(kMaxInstances));
    for (std::size_t i = 0; i < listed.size(); ++i)
      scene.instances.push_back(parse_instance(listed[i], {name, fmt::format("instances[{}]", i)},
                                               bounds, model_of, ground));
    const nlohmann::json defaults = j.value("scatter_defaults", nlohmann::json::object());
    if (!defaults.is_object()) fail(name, "scatter_defaults: must be an object");
    const nlohmann::json& scatters = array_of(j, "scatter", name, kMaxScatters);
    for (std::size_t i = 0; i < scatters.size(); ++i) {
      const Where w{name, fmt::format("scatter[{}]", i)};
      if (!scatters[i].is_object()) fail(name, fmt::format("{}: must be an object", w.path));
      nlohmann::json merged = defaults;
      merged.update(scatters[i]);
      const Scatter sc = parse_scatter(merged, w, h, model_of);
      if (double(scene.instances.size()) + double(sc.count) > double(kMaxInstances))
        w.fail("count", fmt::format(" {}: the scene would hold more than {} instances", sc.count,
                                    kMaxInstances));
      scatter(sc, w, scene.models[sc.model].name, h, ground, scene.instances);
    }
  } catch (const nlohmann::json::exception& e) {
    // A parse error quotes the token it stopped in, which may be the whole file.
    const std::string what = e.what();
    fail(name, fmt::format("not a valid scene file ({}{})", what.substr(0, 200),
                           what.size() > 200 ? "..." : ""));
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
