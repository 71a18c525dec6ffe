// SPDX-License-Identifier: MIT
// `bench hybrid --quality-diagnosis FILE`: why the walkthrough's object
// SSIM is not what the quality tables predict. At each checkpoint the
// visible instances are split by on-screen size; each group is drawn alone
// at full geometry and at one representation for all (every LOD level,
// relief and octahedral resolution), over the terrain (the scene's
// condition) and over the sky colour (the tables' condition), optionally at
// a multiple of the image size; each pair is scored as the bench scores
// (luma SSIM over the pixels the group covers in either image) next to the
// tables' prediction (expected SSIM weighted by the instances' pixels).
#include <fmt/format.h>

#include <map>
#include <nlohmann/json.hpp>

#include "gl/render_target.h"
#include "hybrid_bench.h"
#include "terrasprite/expected_quality.h"
#include "terrasprite/instance_view.h"
#include "terrasprite/mesh_renderer.h"
#include "terrasprite/quality.h"

namespace terrasprite::cli {
namespace {

struct Item {
  std::size_t model, instance;
  InstanceView view;
};

/// Draws a list of instances, each with the representation `rep_of` gives.
class AssignedObjects : public SceneObjects {
 public:
  AssignedObjects(ObjectSet& set, const std::vector<Item>& items,
                  std::function<Representation(std::size_t model)> rep_of)
      : set_(set), items_(items), rep_of_(std::move(rep_of)) {}
  long long draw(const Camera& camera) override {
    std::map<std::tuple<std::size_t, int, int, int>,
             std::pair<Representation, std::vector<ObjectInstance>>>
        groups;
    for (const Item& it : items_) {
      const Representation r = rep_of_(it.model);
      auto& g = groups[{it.model, int(r.kind), r.level, r.resolution}];
      g.first = r;
      g.second.push_back(set_.instances(it.model)[it.instance]);
    }
    long long tri = 0;
    for (auto& [key, g] : groups) {
      set_.model(std::get<0>(key)).draw(g.first, g.second, camera);
      tri += set_.model(std::get<0>(key)).triangles(g.first) * (long long)g.second.size();
    }
    return tri;
  }

 private:
  ObjectSet& set_;
  const std::vector<Item>& items_;
  std::function<Representation(std::size_t)> rep_of_;
};

/// One image: colour and depth (metres; +inf where nothing was drawn).
struct Shot {
  Image color;
  std::vector<float> depth;
  double ms = 0;  ///< the draw, terrain included (median of `repeats` over the terrain)
};

/// A representation for every model: kind plus level (meshes, clamped to
/// the model's coarsest) or resolution (impostors).
struct Uniform {
  ObjectKind kind;
  int level_or_res;
  std::string label() const {
    return kind == ObjectKind::kMesh ? fmt::format("pm L{}", level_or_res)
                                     : fmt::format("{} {}", object_kind_name(kind), level_or_res);
  }
};

}  // namespace

nlohmann::json diagnose_hybrid_quality(const QualityDiagnosisInput& in) {
  ObjectSet& set = in.set;
  std::vector<Uniform> uniforms;
  {
    int levels = 0;
    std::vector<int> relief, octa;
    for (const QualityTable& t : in.tables)
      for (const RepresentationQuality& r : t.representations) {
        if (r.rep.kind == ObjectKind::kMesh) levels = std::max(levels, r.rep.level + 1);
        auto& v = r.rep.kind == ObjectKind::kRelief ? relief : octa;
        if (r.rep.kind != ObjectKind::kMesh &&
            std::find(v.begin(), v.end(), r.rep.resolution) == v.end())
          v.push_back(r.rep.resolution);
      }
    std::sort(relief.begin(), relief.end());
    std::sort(octa.begin(), octa.end());
    for (int l = 1; l < levels; ++l) uniforms.push_back({ObjectKind::kMesh, l});
    for (int r : relief) uniforms.push_back({ObjectKind::kRelief, r});
    for (int r : octa) uniforms.push_back({ObjectKind::kOctahedral, r});
  }
  auto rep_for = [&](const Uniform& u, std::size_t m) -> Representation {
    if (u.kind == ObjectKind::kMesh)
      return {ObjectKind::kMesh, std::min(u.level_or_res, int(set.model(m).chain().size()) - 1), 0,
              0};
    for (const RepresentationQuality& r : in.tables[m].representations)
      if (r.rep.kind == u.kind && r.rep.resolution == u.level_or_res) return r.rep;
    return {};
  };
  // The tables' interpolators, by model and representation.
  std::vector<std::map<std::tuple<int, int, int>, QualityInterpolator>> interp(set.model_count());
  for (std::size_t m = 0; m < set.model_count(); ++m)
    for (const RepresentationQuality& r : in.tables[m].representations)
      interp[m].emplace(std::make_tuple(int(r.rep.kind), r.rep.level, r.rep.resolution),
                        QualityInterpolator(r));

  const std::vector<double> edges = {0, 4, 8, 16, 32, 64, 1e9};
  nlohmann::json out = nlohmann::json::array();
  for (const std::string& condition : in.conditions) {
    const int scale = condition == "scene4" ? 4 : 1;
    const bool sky = condition == "sky";
    const int w = in.width * scale, h = in.height * scale;
    MeshRenderer terrain(in.ground, w, h, in.terrain_quads,
                         RasterOptions{.drape_filter = DrapeFilter::kHand});
    gl::RenderTarget target(w, h);
    auto shoot = [&](SceneObjects& objects, const Camera& cam, int repeats = 1) {
      Shot s;
      if (sky) {
        target.bind_and_clear();
        objects.draw(cam);
        s.color = target.read_color();
        s.depth = target.read_depth(cam.near_m, cam.far_m);
      } else {
        in.ground.set_objects(&objects);
        Frame f;
        std::vector<double> ms;
        for (int k = 0; k < repeats; ++k) {
          f = terrain.draw(cam);
          ms.push_back(f.ms);
        }
        std::sort(ms.begin(), ms.end());
        s.ms = ms[ms.size() / 2];
        in.ground.set_objects(nullptr);
        terrain.read_back(f, ReadBack::kColorDepth);
        s.color = std::move(f.color);
        s.depth = std::move(f.depth);
      }
      return s;
    };
    for (const PathCheckpoint& cp : in.checkpoints) {
      const Camera& cam = in.path[std::size_t(cp.frame)];
      std::vector<Item> all;
      for (std::size_t m = 0; m < set.model_count(); ++m) {
        const Model& model = set.model(m).model();
        const auto inst = set.instances(m);
        for (std::size_t i = 0; i < inst.size(); ++i) {
          const InstanceView v = view_instance(cam, h, inst[i], glm::dvec3(model.center()),
                                               model.bounding_radius());
          if (v.visible) all.push_back({m, i, v});
        }
      }
      const std::vector<Item> none;
      AssignedObjects empty(set, none, [](std::size_t) { return Representation{}; });
      const Shot bare = shoot(empty, cam);
      // Groups: by on-screen size (px at the base image size), by model, all.
      std::vector<std::pair<std::string, std::vector<Item>>> groups;
      for (std::size_t b = 0; b + 1 < edges.size(); ++b) {
        std::vector<Item> items;
        for (const Item& it : all)
          if (it.view.size_px / scale >= edges[b] && it.view.size_px / scale < edges[b + 1])
            items.push_back(it);
        groups.push_back({b + 2 == edges.size() ? fmt::format(">={}", edges[b])
                                                : fmt::format("{}-{}", edges[b], edges[b + 1]),
                          items});
      }
      for (std::size_t m = 0; m < set.model_count(); ++m) {
        std::vector<Item> items;
        for (const Item& it : all)
          if (it.model == m) items.push_back(it);
        groups.push_back({set.scene_model(m).name, items});
      }
      groups.push_back({"all", all});
      for (const auto& [bucket, items] : groups) {
        const bool every = bucket == "all";
        if (items.empty()) continue;
        AssignedObjects full(set, items, [](std::size_t) { return Representation{}; });
        const Shot ref = shoot(full, cam, every ? 3 : 1);
        if (every && !in.image_dir.empty())
          save_png(ref.color, fmt::format("{}/{}_{}_full.png", in.image_dir, condition, cp.name));
        for (const Uniform& u : uniforms) {
          AssignedObjects test_objects(set, items, [&](std::size_t m) { return rep_for(u, m); });
          const Shot test = shoot(test_objects, cam, every ? 3 : 1);
          if (every && !in.image_dir.empty()) {
            std::string label = u.label();
            std::replace(label.begin(), label.end(), ' ', '_');
            save_png(test.color,
                     fmt::format("{}/{}_{}_{}.png", in.image_dir, condition, cp.name, label));
          }
          std::vector<std::uint8_t> mask(ref.depth.size());
          std::size_t covered = 0;
          auto front = [&](float d, std::size_t i) {
            return std::isfinite(d) && !(d >= bare.depth[i] * 0.9995f - 1e-3f);
          };
          for (std::size_t i = 0; i < mask.size(); ++i) {
            mask[i] = front(ref.depth[i], i) || front(test.depth[i], i);
            covered += mask[i];
          }
          double predicted = 0, wsum = 0;
          for (const Item& it : items) {
            const Representation r = rep_for(u, it.model);
            const auto f =
                interp[it.model].find(std::make_tuple(int(r.kind), r.level, r.resolution));
            const double q = f == interp[it.model].end()
                                 ? 1.0
                                 : f->second.at(it.view.phi_deg, it.view.theta_deg, it.view.size_px)
                                       .ssim;
            predicted += it.view.pixels * q;
            wsum += it.view.pixels;
          }
          double measured = 1.0;
          if (covered && ref.color.rgba != test.color.rgba) {
            quality::SsimOptions so;
            so.channels = false;
            measured = quality::ssim(ref.color.view(), test.color.view(), so, mask).ssim;
          }
          out.push_back({{"condition", condition},
                         {"checkpoint", cp.name},
                         {"bucket", bucket},
                         {"instances", items.size()},
                         {"covered_px", covered},
                         {"representation", u.label()},
                         {"predicted", wsum > 0 ? predicted / wsum : 1.0},
                         {"measured", measured},
                         {"ms", test.ms},
                         {"ms_full", ref.ms}});
          fmt::print(stderr,
                     "{:7} {} {:>6} n={:3} px={:6} {:14} predicted {:.3f} measured {:.3f} {:.1f} "
                     "ms (full {:.1f})\n",
                     condition, cp.name, bucket, items.size(), covered, u.label(),
                     wsum > 0 ? predicted / wsum : 1.0, measured, test.ms, ref.ms);
        }
      }
    }
  }
  return out;
}

}  // namespace terrasprite::cli
