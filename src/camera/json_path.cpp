// SPDX-License-Identifier: MIT
// JSON keyframe paths: Catmull-Rom positions, slerped orientations.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#include "terrasprite/camera/camera_path.h"
#include "terrasprite/common/error.h"
#include "terrasprite/terrain/geo_frame.h"

namespace terrasprite {
namespace {

// Positions and targets farther than this from the terrain centre (metres) are
// a mistake (degrees for metres, a stray exponent), not a flight.
constexpr double kMaxCoordinateM = 1e7;
// Keyframe times beyond this (seconds, about 30 years) lose the precision that
// uniform sampling in t needs.
constexpr double kMaxTimeS = 1e9;

struct Key {
  double t;
  glm::dvec3 pos;
  glm::dquat orient;  // camera-local (right, up, back) -> world
  double fov;
};

glm::dquat orientation_of(const Camera& c) {
  glm::dmat3 m(c.right(), c.up(), -c.forward());
  return glm::normalize(glm::quat_cast(m));
}

void set_orientation(Camera& c, const glm::dquat& q) {
  glm::dvec3 f = -(q * glm::dvec3(0, 0, 1)), u = q * glm::dvec3(0, 1, 0);
  Camera tmp = Camera::look_at(glm::dvec3(0), f, c.fov_y_deg, c.aspect, c.yaw_deg);
  c.yaw_deg = tmp.yaw_deg;
  c.pitch_deg = tmp.pitch_deg;
  c.roll_deg = 0;
  glm::dvec3 r0 = c.right(), u0 = c.up();
  c.roll_deg = std::atan2(glm::dot(u, r0), glm::dot(u, u0)) / kRadiansPerDegree;
}

glm::dvec3 vec3_of(const nlohmann::json& j, const std::string& where) {
  if (!j.is_array() || j.size() != 3 || !j[0].is_number() || !j[1].is_number() || !j[2].is_number())
    throw InputError(where + " must be an array of 3 numbers");
  const glm::dvec3 v(j[0].get<double>(), j[1].get<double>(), j[2].get<double>());
  for (int c = 0; c < 3; ++c)
    if (!(std::abs(v[c]) <= kMaxCoordinateM))
      throw InputError(fmt::format("{} [{}, {}, {}]: coordinates must be finite and within {:g} m",
                                   where, v[0], v[1], v[2], kMaxCoordinateM));
  return v;
}

double number_of(const nlohmann::json& k, const char* key, double fallback,
                 const std::string& where) {
  if (!k.contains(key)) return fallback;
  if (!k[key].is_number()) throw InputError(fmt::format("{}.{} must be a number", where, key));
  double v = k[key].get<double>();
  if (!std::isfinite(v)) throw InputError(fmt::format("{}.{} must be finite", where, key));
  return v;
}

nlohmann::json parse_document(std::string_view text, const std::string& path) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(fmt::format("{}: malformed JSON at byte {}", path, e.byte));
  } catch (const nlohmann::json::exception& e) {
    // e.g. a number too large for a double (1e999): out_of_range, not parse_error.
    std::string why = e.what();
    std::replace(why.begin(), why.end(), '\n', ' ');
    throw InputError(fmt::format("{}: unreadable JSON ({})", path, why));
  }
}

// "lon" and "lat" of `k` (both required), degrees.
GeoPlace geo_place_of(const nlohmann::json& k, const std::string& where) {
  if (!k.is_object() || !k.contains("lon") || !k.contains("lat"))
    throw InputError(where + " needs both \"lon\" and \"lat\" (WGS 84 degrees)");
  GeoPlace g;
  g.lon = number_of(k, "lon", 0.0, where);
  g.lat = number_of(k, "lat", 0.0, where);
  if (!(g.lat >= -90 && g.lat <= 90))
    throw InputError(fmt::format("{}.lat {}: must be within -90 .. 90 degrees", where, g.lat));
  if (!(g.lon >= -180 && g.lon <= 360))
    throw InputError(fmt::format("{}.lon {}: must be within -180 .. 360 degrees", where, g.lon));
  return g;
}

// The eye: "position" in metres, or "lon", "lat" with "alt_m" or "agl_m".
void keyframe_eye(const nlohmann::json& k, const std::string& where, PathKeyframe& key) {
  const bool geo = k.contains("lon") || k.contains("lat");
  if (geo && k.contains("position"))
    throw InputError(where + ": give \"position\" or \"lon\"/\"lat\", not both");
  if (!geo) {
    if (!k.contains("position")) throw InputError(where + " has no position (or lon/lat)");
    key.position = vec3_of(k["position"], where + ".position");
    return;
  }
  GeoPlace g = geo_place_of(k, where);
  if (k.contains("alt_m") == k.contains("agl_m"))
    throw InputError(where +
                     ": with lon/lat give one of \"alt_m\" (above sea level) or "
                     "\"agl_m\" (above ground)");
  g.above_ground = k.contains("agl_m");
  g.height_m = number_of(k, g.above_ground ? "agl_m" : "alt_m", 0.0, where);
  if (!(std::abs(g.height_m) <= kMaxCoordinateM))
    throw InputError(fmt::format("{}.{} {}: must be within {:g} m", where,
                                 g.above_ground ? "agl_m" : "alt_m", g.height_m, kMaxCoordinateM));
  if (g.above_ground && g.height_m < 0)
    throw InputError(fmt::format("{}.agl_m {}: must not be negative", where, g.height_m));
  key.geo_position = g;
}

// Keyframe `k`, checked; `where` names it in errors.
PathKeyframe keyframe_of(const nlohmann::json& k, const std::string& where) {
  if (!k.is_object()) throw InputError(where + " must be an object");
  if (!k.contains("t") || !k["t"].is_number())
    throw InputError(where + ".t must be a number (seconds)");
  PathKeyframe key;
  key.t = k["t"].get<double>();
  if (!(std::abs(key.t) <= kMaxTimeS))
    throw InputError(
        fmt::format("{}.t {}: must be finite and within {:g} s", where, key.t, kMaxTimeS));
  keyframe_eye(k, where, key);
  key.fov_deg = number_of(k, "fov_deg", 60.0, where);
  if (!(key.fov_deg > 0 && key.fov_deg < 180))
    throw InputError(where + ".fov_deg must be in (0, 180)");
  if (k.contains("target") && k.contains("look_at"))
    throw InputError(where + ": give \"target\" or \"look_at\", not both");
  if (k.contains("target")) {
    key.target = vec3_of(k["target"], where + ".target");
    if (!key.geo_position && glm::length(*key.target - key.position) <= 0)
      throw InputError(where + ".target equals its position");
    key.roll_deg = number_of(k, "roll_deg", 0.0, where);
  } else if (k.contains("look_at")) {
    key.geo_target = geo_place_of(k["look_at"], where + ".look_at");
    key.roll_deg = number_of(k, "roll_deg", 0.0, where);
  } else if (k.contains("yaw_deg") || k.contains("pitch_deg")) {
    key.yaw_deg = number_of(k, "yaw_deg", 0.0, where);
    key.pitch_deg = number_of(k, "pitch_deg", 0.0, where);
    key.roll_deg = number_of(k, "roll_deg", 0.0, where);
    if (std::abs(key.pitch_deg) > 90) throw InputError(where + ".pitch_deg must be in [-90, 90]");
  } else {
    throw InputError(where + " needs \"target\", \"look_at\" or \"yaw_deg\"/\"pitch_deg\"");
  }
  return key;
}

// The document's checkpoints (none without the key), within [t0, t1].
std::vector<PathCheckpoint> checkpoints_of(const nlohmann::json& doc, const std::string& name,
                                           double t0, double t1) {
  std::vector<PathCheckpoint> out;
  if (!doc.contains("checkpoints")) return out;
  if (!doc["checkpoints"].is_array())
    throw InputError(fmt::format("{}: \"checkpoints\" must be an array", name));
  for (std::size_t i = 0; i < doc["checkpoints"].size(); ++i) {
    const auto& c = doc["checkpoints"][i];
    const std::string where = fmt::format("{}: checkpoints[{}]", name, i);
    if (!c.is_object() || !c.contains("name") || !c["name"].is_string() ||
        c["name"].get<std::string>().empty())
      throw InputError(where + ": needs a non-empty \"name\"");
    if (!c.contains("t") || !c["t"].is_number() || !std::isfinite(c["t"].get<double>()))
      throw InputError(where + ": needs a number \"t\" (seconds)");
    const double t = c["t"].get<double>();
    if (!(t >= t0 && t <= t1))
      throw InputError(
          fmt::format("{}: t {} is outside the keyframes' span [{}, {}]", where, t, t0, t1));
    out.push_back({c["name"].get<std::string>(), t, 0});
  }
  return out;
}

// The keyframes' orientations (camera-local to world), each on the shorter
// arc from the one before.
std::vector<Key> keys_of(const KeyframePath& path, double aspect) {
  std::vector<Key> keys;
  for (const PathKeyframe& k : path.keyframes) {
    Camera c;
    if (k.target) {
      c = Camera::look_at(k.position, *k.target, k.fov_deg, aspect, 0.0);
    } else {
      c.yaw_deg = k.yaw_deg;
      c.pitch_deg = k.pitch_deg;
    }
    c.roll_deg = k.roll_deg;
    Key key{k.t, k.position, orientation_of(c), k.fov_deg};
    if (!keys.empty() && glm::dot(keys.back().orient, key.orient) < 0)
      key.orient = -key.orient;  // shortest arc
    keys.push_back(key);
  }
  return keys;
}

glm::dvec3 catmull_rom(const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& p2,
                       const glm::dvec3& p3, double u) {
  double u2 = u * u, u3 = u2 * u;
  return 0.5 * ((2.0 * p1) + (-p0 + p2) * u + (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * u2 +
                (-p0 + 3.0 * p1 - 3.0 * p2 + p3) * u3);
}

}  // namespace

KeyframePath parse_path_json(std::string_view text, const std::string& path) {
  const nlohmann::json doc = parse_document(text, path);
  if (!doc.is_object() || !doc.contains("keyframes") || !doc["keyframes"].is_array() ||
      doc["keyframes"].empty())
    throw InputError(fmt::format("{}: needs a non-empty \"keyframes\" array", path));
  KeyframePath out;
  out.name = path;
  for (std::size_t i = 0; i < doc["keyframes"].size(); ++i) {
    const std::string where = fmt::format("{}: keyframes[{}]", path, i);
    PathKeyframe key = keyframe_of(doc["keyframes"][i], where);
    if (!out.keyframes.empty() && !(key.t > out.keyframes.back().t))
      throw InputError(where + ".t must be greater than the previous keyframe's");
    out.keyframes.push_back(key);
  }
  out.checkpoints = checkpoints_of(doc, path, out.keyframes.front().t, out.keyframes.back().t);
  return out;
}

namespace {

// `path` with its geographic places put on `h` in world metres.
KeyframePath placed_on(const KeyframePath& path, const Heightfield& h) {
  KeyframePath out = path;
  std::optional<GeoFrame> frame;
  for (std::size_t i = 0; i < out.keyframes.size(); ++i) {
    PathKeyframe& k = out.keyframes[i];
    if (!k.geo_position && !k.geo_target) continue;
    const std::string where = fmt::format("{}: keyframes[{}]", path.name, i);
    if (!frame) frame.emplace(h, where);
    if (const auto& g = k.geo_position) {
      const WorldXY p =
          frame->world_of(g->lon, g->lat, GeoMargin::kNearTerrain, where + " lon,lat");
      const double ground = h.sample(p.x, p.y);
      k.position = {p.x, p.y, g->above_ground ? ground + g->height_m : g->height_m};
    }
    if (const auto& g = k.geo_target) {
      const WorldXY p = frame->world_of(g->lon, g->lat, GeoMargin::kOnTerrain, where + ".look_at");
      k.target = glm::dvec3(p.x, p.y, h.sample(p.x, p.y));
    }
    if (k.target && glm::length(*k.target - k.position) <= 0)
      throw InputError(where + ": the eye is at its target");
  }
  return out;
}

}  // namespace

std::vector<Camera> sample_path(const KeyframePath& given, const Heightfield& h, int frames,
                                double aspect) {
  if (frames < 1) throw InputError(fmt::format("frames {}: must be at least 1", frames));
  const KeyframePath path = placed_on(given, h);
  const std::vector<Key> keys = keys_of(path, aspect);
  std::vector<Camera> out;
  const double t0 = keys.front().t, t1 = keys.back().t;
  const int n = int(keys.size());
  for (int f = 0; f < frames; ++f) {
    double t = frames == 1 ? t0 : t0 + (t1 - t0) * f / (frames - 1);
    int k = 0;
    while (k + 2 < n && t > keys[k + 1].t) ++k;
    Camera c;
    c.aspect = aspect;
    if (n == 1) {
      c.position = keys[0].pos;
      c.fov_y_deg = keys[0].fov;
      set_orientation(c, keys[0].orient);
    } else {
      const Key &a = keys[k], &b = keys[k + 1];
      double u = std::clamp((t - a.t) / (b.t - a.t), 0.0, 1.0);
      const glm::dvec3& p0 = k > 0 ? keys[k - 1].pos : a.pos;
      const glm::dvec3& p3 = k + 2 < n ? keys[k + 2].pos : b.pos;
      c.position = catmull_rom(p0, a.pos, b.pos, p3, u);
      c.fov_y_deg = a.fov + (b.fov - a.fov) * u;
      set_orientation(c, glm::slerp(a.orient, b.orient, u));
    }
    fit_clip_planes(c, h);
    out.push_back(c);
  }
  return out;
}

std::vector<PathCheckpoint> checkpoint_frames(const KeyframePath& path, int frames) {
  std::vector<PathCheckpoint> out = path.checkpoints;
  if (path.keyframes.empty()) return out;
  const double t0 = path.keyframes.front().t, t1 = path.keyframes.back().t;
  for (PathCheckpoint& c : out)
    c.frame = t1 > t0 ? int(std::lround((c.t - t0) / (t1 - t0) * (frames - 1))) : 0;
  return out;
}

std::vector<Camera> load_path_file(const std::string& path, const Heightfield& h, int frames,
                                   double aspect) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(fmt::format("{}: no such path file", path));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot open path file", path));
  const std::string text((std::istreambuf_iterator<char>(in)), {});
  return path_from_json(text, path, h, frames, aspect);
}

std::vector<Camera> path_from_json(std::string_view text, const std::string& path,
                                   const Heightfield& h, int frames, double aspect) {
  if (frames < 1) throw InputError(fmt::format("frames {}: must be at least 1", frames));
  return sample_path(parse_path_json(text, path), h, frames, aspect);
}

}  // namespace terrasprite
