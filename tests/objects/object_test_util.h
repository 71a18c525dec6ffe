// SPDX-License-Identifier: MIT
// Models and views made in code for the object tests.
#pragma once
#include <cmath>
#include <fstream>
#include <string>

#include "terrasprite/camera/camera.h"
#include "terrasprite/objects/model.h"
#include "terrasprite/objects/object_layout.h"
#include "terrasprite/terrain/terrain.h"
#include "test_util.h"

namespace tstest {

/// The default scene's forest (Kenney decoration-forest.glb), 10 m tall as
/// the scene places it, from `data` (tstest::shared_data(), not empty).
inline terrasprite::Model forest_10m(const std::string& data) {
  terrasprite::ModelOptions o;
  o.height_m = 10;
  return terrasprite::load_model(data + "/models_kenney_racing/decoration-forest.glb", o);
}

/// A square pyramid (a 6-triangle "tower", model "t") written into `dir`, in
/// a scene with the given model keys (height, colour) and instances (a JSON
/// array), placed on `terrain`.
inline terrasprite::ObjectLayout tower_layout(const TempDir& dir,
                                              const terrasprite::Terrain& terrain,
                                              const std::string& model_keys,
                                              const std::string& instances) {
  std::ofstream(dir / "tower.obj") << "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv 0 3 0\n"
                                      "f 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\nf 1 3 2\nf 1 4 3\n";
  return terrasprite::parse_object_layout(R"({"models": [{"name": "t", "file": "tower.obj", )" +
                                              model_keys + R"(}], "instances": )" + instances + "}",
                                          "scene", dir.path.string(), terrain.heights);
}

/// The 65 x 65 synthetic terrain with towers on it (tower_layout's arguments),
/// the scene's files in its own temporary directory.
struct TowerWorld {
  TempDir dir;
  terrasprite::Terrain terrain;
  terrasprite::ObjectLayout objects;
  TowerWorld(const std::string& model_keys, const std::string& instances) {
    terrasprite::TerrainOptions o;
    o.synthetic_size = 65;
    terrain = terrasprite::load_terrain(o);
    objects = tower_layout(dir, terrain, model_keys, instances);
  }
};

/// An axis-aligned box [-sx/2, sx/2] x [-sy/2, sy/2] x [0, sz], each face its
/// own flat colour (+x red, -x green, +y blue, -y yellow, +z white, -z magenta).
inline terrasprite::Model colored_box(float sx = 1.f, float sy = 1.f, float sz = 1.f) {
  using glm::vec3;
  terrasprite::Model m;
  m.name = "box";
  const vec3 lo(-sx / 2, -sy / 2, 0), hi(sx / 2, sy / 2, sz);
  const glm::vec4 colors[6] = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1},
                               {1, 1, 0, 1}, {1, 1, 1, 1}, {1, 0, 1, 1}};
  for (int f = 0; f < 6; ++f) {
    const int a = f / 2, u = (a + 1) % 3, v = (a + 2) % 3;
    const float sign = f % 2 == 0 ? 1.f : -1.f;
    vec3 n(0.f);
    n[a] = sign;
    const std::uint32_t base = std::uint32_t(m.positions.size());
    for (int k = 0; k < 4; ++k) {
      vec3 p;
      p[a] = sign > 0 ? hi[a] : lo[a];
      p[u] = (k & 1) ? hi[u] : lo[u];
      p[v] = (k & 2) ? hi[v] : lo[v];
      m.positions.push_back(p);
      m.normals.push_back(n);
      m.uvs.emplace_back(0.f);
    }
    // Counter-clockwise seen from outside.
    const bool flip = sign < 0;
    const std::uint32_t tri[6] = {0, 1, 3, 0, 3, 2};
    m.parts.push_back({std::uint32_t(m.indices.size()), 6, f});
    for (int k = 0; k < 6; k += 3) {
      m.indices.push_back(base + tri[k]);
      m.indices.push_back(base + tri[k + (flip ? 2 : 1)]);
      m.indices.push_back(base + tri[k + (flip ? 1 : 2)]);
    }
    m.materials.push_back({"face", colors[f], -1});
  }
  m.normals_from_file = true;
  m.bounds_min = lo;
  m.bounds_max = hi;
  return m;
}

/// A camera `dist` metres from `target`, at azimuth `phi_deg` (0 = looking
/// north from the south) and elevation `elev_deg`.
inline terrasprite::Camera orbit(glm::dvec3 target, double dist, double phi_deg, double elev_deg,
                                 double fov_deg = 30.0, double aspect = 1.0) {
  const double p = phi_deg * M_PI / 180, e = elev_deg * M_PI / 180;
  const glm::dvec3 eye = target + dist * glm::dvec3(-std::sin(p) * std::cos(e),
                                                    -std::cos(p) * std::cos(e), std::sin(e));
  terrasprite::Camera c = terrasprite::Camera::look_at(eye, target, fov_deg, aspect);
  c.near_m = dist * 0.1;
  c.far_m = dist * 10;
  return c;
}

}  // namespace tstest
