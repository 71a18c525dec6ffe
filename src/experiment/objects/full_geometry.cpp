// SPDX-License-Identifier: MIT
// `objects scene`: a scene's objects on the terrain at full geometry, all in
// view -- the frame time a budget has to beat.
#include "terrasprite/experiment/objects/full_geometry.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "terrasprite/common/stats.h"
#include "terrasprite/gl/gl_context.h"
#include "terrasprite/objects/gl_scene_objects.h"
#include "terrasprite/objects/object_layout.h"
#include "terrasprite/raster/mesh_renderer.h"
#include "terrasprite/raster/scene.h"

namespace terrasprite {
namespace {

// From the south, 35 degrees down, far enough that every instance is in view.
Camera overview_camera(const GlSceneObjects& set, const Heightfield& h, double aspect) {
  glm::dvec3 lo(INFINITY), hi(-INFINITY);
  for (std::size_t m = 0; m < set.model_count(); ++m)
    for (const ObjectInstance& i : set.instances(m)) {
      lo = glm::min(lo, i.position);
      hi = glm::max(hi, i.position);
    }
  const glm::dvec3 c = 0.5 * (lo + hi);
  const double r = 0.5 * glm::length(hi - lo) + 10.0;
  const double fov = 50.0, dist = r / std::sin(glm::radians(std::min(fov, fov * aspect) / 2));
  const double e = glm::radians(35.0);
  Camera cam = Camera::look_at(c + dist * glm::dvec3(0, -std::cos(e), std::sin(e)), c, fov, aspect);
  fit_clip_planes(cam, h);
  return cam;
}

// The full-resolution renderer with and without the objects, interleaved
// frame by frame; frame 0 warms up (shaders, uploads). The last frame with
// the objects is read back into r.frame.
void time_frames(Scene& ground, GlSceneObjects& objects, const Camera& cam, int frames,
                 FullGeometryResult& r) {
  MeshRenderer full(ground, r.width, r.height, 0);
  for (int f = 0; f <= frames; ++f) {
    ground.set_objects(&objects);
    const Frame a = full.draw(cam);
    if (f == frames) {
      Frame img = a;
      full.read_back(img, ReadBack::kColor);
      r.frame = std::move(img.color);
    }
    ground.set_objects(nullptr);
    const Frame b = full.draw(cam);
    if (f == 0) continue;
    r.frame_ms.push_back(a.ms);
    r.terrain_ms.push_back(b.ms);
    r.frame_triangles = a.triangles;
    r.terrain_triangles = b.triangles;
  }
}

// Every instance as drawn (grounded on the drawn surface), listed by model.
ObjectLayout placed_layout(GlSceneObjects& objects) {
  ObjectLayout out;
  for (std::size_t m = 0; m < objects.model_count(); ++m) {
    out.models.push_back(objects.layout_model(m));
    for (const ObjectInstance& i : objects.instances(m))
      out.instances.push_back({int(m), i, false});
  }
  return out;
}

std::vector<FullGeometryModel> loaded_models(GlSceneObjects& objects) {
  std::vector<FullGeometryModel> models;
  for (std::size_t m = 0; m < objects.model_count(); ++m)
    models.push_back({objects.layout_model(m).name, objects.layout_model(m).file,
                      objects.model(m).model().triangles(), objects.instances(m).size(),
                      objects.model(m).chain().size()});
  return models;
}

}  // namespace

FullGeometryResult run_full_geometry(const FullGeometryOptions& o, const Terrain& terrain) {
  const ObjectLayout scene = o.scene.empty() ? default_object_layout(o.models_dir, terrain.heights)
                                             : load_object_layout(o.scene, terrain.heights);
  FullGeometryResult r;
  r.width = o.width;
  r.height = o.height;
  r.frames = o.frames;
  GlContext gl;
  r.gl_renderer = gl.renderer();
  Scene ground(terrain);
  const auto load_start = std::chrono::steady_clock::now();
  GlSceneObjects objects(scene, LodOptions{}, o.cache_dir);
  r.load_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - load_start)
          .count();
  r.representation_cache = objects.cache_stats();
  r.instances = objects.instance_count();
  r.full_triangles = objects.full_triangles();
  r.models = loaded_models(objects);
  r.placed = placed_layout(objects);
  const Camera cam = overview_camera(objects, terrain.heights, double(o.width) / o.height);
  r.camera = cam;
  time_frames(ground, objects, cam, o.frames, r);
  r.median_ms = median(r.frame_ms);
  r.terrain_median_ms = median(r.terrain_ms);
  return r;
}

}  // namespace terrasprite
