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
// `--budget-sweep FILE` (quality against fixed budgets, no controller) and
// its `--cost-split N` (each frame's time split by kind) are here too.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <tuple>

#include "gl/render_target.h"
#include "hybrid_bench.h"
#include "terrasprite/terrain/image_io.h"
#include "terrasprite/hybrid/expected_quality.h"
#include "terrasprite/hybrid/hybrid_renderer.h"
#include "terrasprite/hybrid/instance_view.h"
#include "terrasprite/raster/mesh_renderer.h"
#include "terrasprite/quality/quality.h"
#include "terrasprite/hybrid/quality_calibration.h"

namespace terrasprite::cli {
namespace {

struct Item {
  std::size_t model, instance;
  InstanceView view;
};

/// Draws a list of instances, each with the representation `rep_of` gives.
class AssignedObjects : public SceneObjects {
 public:
  AssignedObjects(GlSceneObjects& set, const std::vector<Item>& items,
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
  GlSceneObjects& set_;
  const std::vector<Item>& items_;
  std::function<Representation(std::size_t)> rep_of_;
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

/// One image: colour and depth (metres; +inf where nothing was drawn).
struct Shot {
  Image color;
  std::vector<float> depth;
  double ms = 0;  ///< the draw, terrain included (median of `repeats` over the terrain)
};

/// Draws instances over the terrain (or over the clear colour, as the
/// tables do) and reads colour and depth back.
class Shooter {
 public:
  Shooter(Scene& ground, int w, int h, int quads, bool sky, int samples)
      : ground_(ground),
        terrain_(ground, w, h, quads, hybrid_terrain_raster(samples)),
        target_(w, h, samples),
        sky_(sky) {}
  Shot shoot(SceneObjects& objects, const Camera& cam, int repeats = 1) {
    Shot s;
    if (sky_) {
      target_.bind_and_clear();
      objects.draw(cam);
      s.color = target_.read_color();
      s.depth = target_.read_depth(cam.near_m, cam.far_m);
      return s;
    }
    ground_.set_objects(&objects);
    Frame f;
    std::vector<double> ms;
    for (int k = 0; k < repeats; ++k) {
      f = terrain_.draw(cam);
      ms.push_back(f.ms);
    }
    std::sort(ms.begin(), ms.end());
    s.ms = ms[ms.size() / 2];
    ground_.set_objects(nullptr);
    terrain_.read_back(f, ReadBack::kColorDepth);
    s.color = std::move(f.color);
    s.depth = std::move(f.depth);
    return s;
  }

 private:
  Scene& ground_;
  MeshRenderer terrain_;
  gl::RenderTarget target_;
  bool sky_;
};

std::vector<Item> visible_items(GlSceneObjects& set, const Camera& cam, int height) {
  std::vector<Item> all;
  for (std::size_t m = 0; m < set.model_count(); ++m) {
    const Model& model = set.model(m).model();
    const auto inst = set.instances(m);
    for (std::size_t i = 0; i < inst.size(); ++i) {
      const InstanceView v =
          view_instance(cam, height, inst[i], glm::dvec3(model.center()), model.bounding_radius());
      if (v.visible) all.push_back({m, i, v});
    }
  }
  return all;
}

/// Luma SSIM of `test` against `ref` over the pixels either covers in front
/// of `bare` (the terrain alone), as the bench scores; and their count.
std::pair<double, std::size_t> masked_ssim(const Shot& ref, const Shot& test, const Shot& bare) {
  const std::vector<std::uint8_t> mask = object_mask(ref.depth, test.depth, bare.depth);
  const auto covered = std::size_t(std::count(mask.begin(), mask.end(), 1));
  if (!covered || ref.color.rgba == test.color.rgba) return {1.0, covered};
  quality::SsimOptions so;
  so.channels = false;
  return {quality::ssim(ref.color.view(), test.color.view(), so, mask).ssim, covered};
}

using RepKey = std::tuple<int, int, int>;  // kind, level, resolution
RepKey key_of(const Representation& r) {
  return {int(r.kind), r.level, r.resolution};
}

/// The tables' interpolators, by model and representation.
std::vector<std::map<RepKey, QualityInterpolator>> interpolators(
    const std::vector<QualityTable>& tables) {
  std::vector<std::map<RepKey, QualityInterpolator>> out(tables.size());
  for (std::size_t m = 0; m < tables.size(); ++m)
    for (const RepresentationQuality& r : tables[m].representations)
      out[m].emplace(key_of(r.rep), QualityInterpolator(r));
  return out;
}

/// Expected SSIM of the items at their representations, weighted by pixels.
double predicted_ssim(const std::vector<Item>& items,
                      const std::function<Representation(std::size_t)>& rep_of,
                      const std::vector<std::map<RepKey, QualityInterpolator>>& interp) {
  double sum = 0, wsum = 0;
  for (const Item& it : items) {
    const auto f = interp[it.model].find(key_of(rep_of(it.model)));
    const double q =
        f == interp[it.model].end()
            ? 1.0
            : f->second.at(it.view.phi_deg, it.view.theta_deg, it.view.size_px, it.view.heading_deg)
                  .ssim;
    sum += it.view.pixels * q;
    wsum += it.view.pixels;
  }
  return wsum > 0 ? sum / wsum : 1.0;
}

/// Per kind the frame draws: its time alone over the terrain (drawn with
/// only that kind, less the terrain alone) and its share of the whole frame
/// (the whole frame less the frame without it), each the median over
/// `rounds` of differences taken within one round (the machine's pace
/// drifts between rounds), next to its prediction. `objects` selects as it
/// did for `st` at every draw (fixed budget, no hysteresis).
nlohmann::json cost_split(Shooter& shooter, HybridObjects& objects, const Camera& cam,
                          const HybridFrameStats& st, int rounds) {
  using Kinds = std::array<bool, 3>;
  std::vector<Kinds> masks;
  const auto mask_index = [&](const Kinds& m) {  // added on first use
    const auto it = std::find(masks.begin(), masks.end(), m);
    if (it != masks.end()) return std::size_t(it - masks.begin());
    masks.push_back(m);
    return masks.size() - 1;
  };
  const Kinds all{true, true, true};
  const std::size_t whole = mask_index(all), bare = mask_index({});
  struct Split {
    std::size_t kind, only, without;
  };
  std::vector<Split> splits;
  for (std::size_t k = 0; k < 3; ++k) {
    if (st.instances_by_kind[k] == 0) continue;
    Kinds only{}, without = all;
    only[k] = true;
    without[k] = false;
    splits.push_back({k, mask_index(only), mask_index(without)});
  }
  std::vector<std::vector<double>> alone(3), in_frame(3);
  for (int r = 0; r < rounds; ++r) {
    std::vector<double> ms(masks.size());
    // Rotated each round, so no mask always follows the same one.
    for (std::size_t j = 0; j < masks.size(); ++j) {
      const std::size_t i = (j + std::size_t(r)) % masks.size();
      objects.set_drawn_kinds(masks[i]);
      ms[i] = shooter.shoot(objects, cam, 1).ms;
    }
    for (const Split& s : splits) {
      alone[s.kind].push_back(ms[s.only] - ms[bare]);
      in_frame[s.kind].push_back(ms[whole] - ms[s.without]);
    }
  }
  objects.set_drawn_kinds(all);
  nlohmann::json out = nlohmann::json::array();
  for (const Split& sp : splits) {
    const std::size_t k = sp.kind;
    out.push_back({{"kind", object_kind_name(ObjectKind(k))},
                   {"instances", st.instances_by_kind[k]},
                   {"draw_calls", st.draws_by_kind[k]},
                   {"predicted_ms", st.predicted_by_kind_ms[k]},
                   {"alone_ms", summarize(alone[k]).median},
                   {"in_frame_ms", summarize(in_frame[k]).median}});
  }
  return out;
}
}  // namespace

nlohmann::json diagnose_hybrid_quality(const QualityDiagnosisInput& in) {
  GlSceneObjects& set = in.set;
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
  const auto interp = interpolators(in.tables);
  const auto interp_context =
      in.context_tables ? interpolators(*in.context_tables) : decltype(interp){};

  const std::vector<double> edges = {0, 4, 8, 16, 32, 64, 1e9};
  nlohmann::json out = nlohmann::json::array();
  for (const std::string& condition : in.conditions) {
    const int scale = condition == "scene4" ? 4 : 1;
    const int h = in.height * scale;
    Shooter shooter(in.ground, in.width * scale, h, in.terrain_quads, condition == "sky",
                    in.samples);
    for (const PathCheckpoint& cp : in.checkpoints) {
      const Camera& cam = in.path[std::size_t(cp.frame)];
      const std::vector<Item> all = visible_items(set, cam, h);
      const std::vector<Item> none;
      AssignedObjects empty(set, none, [](std::size_t) { return Representation{}; });
      const Shot bare = shooter.shoot(empty, cam);
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
        groups.push_back({set.layout_model(m).name, items});
      }
      groups.push_back({"all", all});
      for (const auto& [bucket, items] : groups) {
        const bool every = bucket == "all";
        if (items.empty()) continue;
        AssignedObjects full(set, items, [](std::size_t) { return Representation{}; });
        const Shot ref = shooter.shoot(full, cam, every ? 3 : 1);
        if (every && !in.image_dir.empty())
          save_png(ref.color, fmt::format("{}/{}_{}_full.png", in.image_dir, condition, cp.name));
        double theta = 0, size = 0, wsum = 0;
        for (const Item& it : items) {
          theta += it.view.pixels * it.view.theta_deg;
          size += it.view.pixels * it.view.size_px;
          wsum += it.view.pixels;
        }
        for (const Uniform& u : uniforms) {
          const auto rep_of = [&](std::size_t m) { return rep_for(u, m); };
          AssignedObjects test_objects(set, items, rep_of);
          const Shot test = shooter.shoot(test_objects, cam, every ? 3 : 1);
          if (every && !in.image_dir.empty()) {
            std::string label = u.label();
            std::replace(label.begin(), label.end(), ' ', '_');
            save_png(test.color,
                     fmt::format("{}/{}_{}_{}.png", in.image_dir, condition, cp.name, label));
          }
          const auto [measured, covered] = masked_ssim(ref, test, bare);
          const double predicted = predicted_ssim(items, rep_of, interp);
          nlohmann::json row = {{"condition", condition},
                                {"checkpoint", cp.name},
                                {"bucket", bucket},
                                {"instances", items.size()},
                                {"covered_px", covered},
                                {"theta_deg", wsum > 0 ? theta / wsum : 0.0},
                                {"size_px", wsum > 0 ? size / wsum : 0.0},
                                {"representation", u.label()},
                                {"predicted", predicted},
                                {"measured", measured},
                                {"ms", test.ms},
                                {"ms_full", ref.ms}};
          if (in.context_tables)
            row["predicted_context"] = predicted_ssim(items, rep_of, interp_context);
          out.push_back(row);
          fmt::print(stderr,
                     "{:7} {} {:>10} n={:3} px={:6} {:14} predicted {:.3f}{} measured {:.3f} "
                     "{:.1f} ms (full {:.1f})\n",
                     condition, cp.name, bucket, items.size(), covered, u.label(), predicted,
                     in.context_tables ? fmt::format(" (in context {:.3f})",
                                                     row["predicted_context"].get<double>())
                                       : "",
                     measured, test.ms, ref.ms);
        }
      }
    }
  }
  return out;
}

nlohmann::json calibrate_tables_in_context(const QualityContextInput& in,
                                           std::vector<QualityTable>& tables) {
  GlSceneObjects& set = in.set;
  const auto interp = interpolators(tables);
  // Observations per model and representation (the table's row index).
  std::vector<std::vector<std::vector<QualityObservation>>> obs(tables.size());
  for (std::size_t m = 0; m < tables.size(); ++m) obs[m].resize(tables[m].representations.size());
  Shooter shooter(in.ground, in.width, in.height, in.terrain_quads, false, in.samples);
  for (const Camera& cam : in.cameras) {
    const std::vector<Item> all = visible_items(set, cam, in.height);
    const std::vector<Item> none;
    AssignedObjects empty(set, none, [](std::size_t) { return Representation{}; });
    const Shot bare = shooter.shoot(empty, cam);
    for (std::size_t m = 0; m < tables.size(); ++m) {
      // Meshes: every visible instance; impostors: those they are offered to
      // (not past max_impostor_size_px, not within two radii of the camera).
      std::array<std::vector<Item>, 2> items;
      const double radius = set.model(m).model().bounding_radius();
      for (const Item& it : all) {
        if (it.model != m) continue;
        items[0].push_back(it);
        const double r = radius * set.instances(m)[it.instance].scale;
        if (!(in.max_impostor_size_px > 0 &&
              (it.view.size_px > in.max_impostor_size_px || it.view.distance_m < 2 * r)))
          items[1].push_back(it);
      }
      std::array<std::optional<Shot>, 2> ref;
      for (std::size_t k = 0; k < tables[m].representations.size(); ++k) {
        const Representation rep = tables[m].representations[k].rep;
        if (rep.kind == ObjectKind::kMesh && rep.level == 0) continue;
        const std::size_t g = rep.kind == ObjectKind::kMesh ? 0 : 1;
        if (items[g].empty()) continue;
        if (!ref[g]) {
          AssignedObjects full(set, items[g], [](std::size_t) { return Representation{}; });
          ref[g] = shooter.shoot(full, cam);
        }
        const auto rep_of = [&](std::size_t) { return rep; };
        AssignedObjects test_objects(set, items[g], rep_of);
        const Shot test = shooter.shoot(test_objects, cam);
        const auto [measured, covered] = masked_ssim(*ref[g], test, bare);
        if (covered)
          obs[m][k].push_back(
              {predicted_ssim(items[g], rep_of, interp), measured, double(covered)});
      }
    }
  }
  nlohmann::json report = nlohmann::json::array();
  for (std::size_t m = 0; m < tables.size(); ++m)
    for (std::size_t k = 0; k < tables[m].representations.size(); ++k) {
      RepresentationQuality& rq = tables[m].representations[k];
      if (obs[m][k].empty()) continue;
      const double scale = fit_error_scale(obs[m][k]);
      double p = 0, q = 0, w = 0;
      for (const QualityObservation& o : obs[m][k]) {
        p += o.weight * o.predicted;
        q += o.weight * o.measured;
        w += o.weight;
      }
      apply_error_scale(rq, scale);
      report.push_back({{"model", set.layout_model(m).name},
                        {"kind", object_kind_name(rq.rep.kind)},
                        {"level", rq.rep.level},
                        {"resolution", rq.rep.resolution},
                        {"error_scale", scale},
                        {"predicted", w > 0 ? p / w : 1.0},
                        {"measured", w > 0 ? q / w : 1.0},
                        {"pixels", w}});
    }
  return report;
}

nlohmann::json quality_budget_sweep(const BudgetSweepInput& in) {
  nlohmann::json out = nlohmann::json::array();
  Shooter shooter(in.ground, in.width, in.height, in.terrain_quads, false, in.samples);
  // The budget fractions are of full geometry's predicted time.
  const HybridScenario full_scenario = full_geometry_scenario();
  HybridOptions o = in.options;
  o.use_hysteresis = false;
  for (const PathCheckpoint& cp : in.checkpoints) {
    const Camera& cam = in.path[std::size_t(cp.frame)];
    const std::vector<Item> none;
    AssignedObjects empty(in.set, none, [](std::size_t) { return Representation{}; });
    const Shot bare = shooter.shoot(empty, cam, 3);
    HybridObjects full(in.set, in.tables, in.cost, full_scenario, o);
    const Shot ref = shooter.shoot(full, cam, 3);
    const double full_predicted = full.last().predicted_ms;
    // Each scenario as configured; from the tables as measured too; and,
    // when small instances may be left out, with every instance drawn.
    std::vector<std::tuple<HybridScenario, const std::vector<QualityTable>*, double>> runs;
    for (HybridScenario sc : in.scenarios) {
      sc.control = HybridScenario::Control::kFixed;
      runs.push_back({sc, &in.tables, in.options.cull_px});
      if (in.options.cull_px > 0) {
        HybridScenario all_drawn = sc;
        all_drawn.name += " (all drawn)";
        runs.push_back({all_drawn, &in.tables, 0.0});
      }
      if (in.raw_tables) {
        sc.name += " (tables as measured)";
        runs.push_back({sc, in.raw_tables, in.options.cull_px});
      }
    }
    for (double f : in.fractions)
      for (const auto& [sc, tables, cull_px] : runs) {
        o.target_ms = f * full_predicted;
        o.cull_px = cull_px;
        HybridObjects objects(in.set, *tables, in.cost, sc, o);
        objects.prepare();
        const Shot test = shooter.shoot(objects, cam, 3);
        const auto [measured, covered] = masked_ssim(ref, test, bare);
        quality::SsimOptions so;
        so.channels = false;
        const double whole = ref.color.rgba == test.color.rgba
                                 ? 1.0
                                 : quality::ssim(ref.color.view(), test.color.view(), so).ssim;
        const HybridFrameStats& st = objects.last();
        out.push_back({{"checkpoint", cp.name},
                       {"scenario", sc.name},
                       {"fraction", f},
                       {"budget_ms", o.target_ms},
                       {"predicted_ms", st.predicted_ms},
                       {"ms", test.ms},
                       {"full_ms", ref.ms},
                       {"full_predicted_ms", full_predicted},
                       {"terrain_ms", bare.ms},
                       {"expected_ssim", st.expected_ssim},
                       {"ssim_objects", measured},
                       {"ssim", whole},
                       {"triangles", st.triangles},
                       {"by_kind", st.instances_by_kind}});
        fmt::print(stderr,
                   "{} {:34} budget {:.2f} x full ({:6.1f} ms): predicted {:6.1f} ms, measured "
                   "{:6.1f} ms (full {:6.1f}, terrain {:5.1f}); expected SSIM {:.3f}, objects "
                   "{:.3f}, whole {:.4f}; mesh/relief/octahedral {}/{}/{}\n",
                   cp.name, sc.name, f, o.target_ms, st.predicted_ms, test.ms, ref.ms, bare.ms,
                   st.expected_ssim, measured, whole, st.instances_by_kind[0],
                   st.instances_by_kind[1], st.instances_by_kind[2]);
        if (in.cost_split_rounds > 0) {
          const HybridFrameStats drawn = st;  // the draws below select again
          nlohmann::json split = cost_split(shooter, objects, cam, drawn, in.cost_split_rounds);
          for (const nlohmann::json& k : split)
            fmt::print(stderr,
                       "  {:10} x {:3} in {:2} calls: predicted {:6.2f} ms, alone {:6.2f} ms, in "
                       "the frame {:6.2f} ms\n",
                       k["kind"].get<std::string>(), k["instances"].get<int>(),
                       k["draw_calls"].get<int>(), k["predicted_ms"].get<double>(),
                       k["alone_ms"].get<double>(), k["in_frame_ms"].get<double>());
          out.back()["cost_split"] = std::move(split);
        }
      }
  }
  return out;
}

}  // namespace terrasprite::cli
