// SPDX-License-Identifier: MIT
// The walkthrough's quality diagnosis: why the walkthrough's object
// SSIM is not what the quality tables predict. At each checkpoint the
// visible instances are split by on-screen size; each group is drawn alone
// at full geometry and at one representation for all (every LOD level,
// relief and octahedral resolution), over the terrain (the scene's
// condition) and over the sky colour (the tables' condition), optionally at
// a multiple of the image size; each pair is scored as the bench scores
// (luma SSIM over the pixels the group covers in either image) next to the
// tables' prediction (expected SSIM weighted by the instances' pixels).
// The budget sweep (quality against fixed budgets, no controller) and its
// cost split (each frame's time split by kind) are here too, and the tables
// in context, which share the drawing of instance groups.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <optional>
#include <tuple>

#include "gl/render_target.h"
#include "hybrid_stages.h"
#include "terrasprite/terrain/image_io.h"
#include "terrasprite/hybrid/expected_quality.h"
#include "terrasprite/hybrid/hybrid_renderer.h"
#include "terrasprite/hybrid/instance_view.h"
#include "terrasprite/raster/mesh_renderer.h"
#include "terrasprite/quality/quality.h"
#include "terrasprite/hybrid/quality_calibration.h"

namespace terrasprite::hybrid_bench {
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
std::vector<CostSplitRow> cost_split(Shooter& shooter, HybridObjects& objects, const Camera& cam,
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
  std::vector<CostSplitRow> out;
  for (const Split& sp : splits) {
    const std::size_t k = sp.kind;
    out.push_back({ObjectKind(k), st.instances_by_kind[k], st.draws_by_kind[k],
                   st.predicted_by_kind_ms[k], summarize(alone[k]).median,
                   summarize(in_frame[k]).median});
  }
  return out;
}
/// The uniform representations the diagnosis tries: every LOD level past
/// full geometry, then every relief and octahedral resolution in the tables.
std::vector<Uniform> diagnosis_uniforms(const std::vector<QualityTable>& tables) {
  int levels = 0;
  std::vector<int> relief, octa;
  for (const QualityTable& t : tables)
    for (const RepresentationQuality& r : t.representations) {
      if (r.rep.kind == ObjectKind::kMesh) levels = std::max(levels, r.rep.level + 1);
      auto& v = r.rep.kind == ObjectKind::kRelief ? relief : octa;
      if (r.rep.kind != ObjectKind::kMesh &&
          std::find(v.begin(), v.end(), r.rep.resolution) == v.end())
        v.push_back(r.rep.resolution);
    }
  std::sort(relief.begin(), relief.end());
  std::sort(octa.begin(), octa.end());
  std::vector<Uniform> uniforms;
  for (int l = 1; l < levels; ++l) uniforms.push_back({ObjectKind::kMesh, l});
  for (int r : relief) uniforms.push_back({ObjectKind::kRelief, r});
  for (int r : octa) uniforms.push_back({ObjectKind::kOctahedral, r});
  return uniforms;
}

/// Model m's representation for `u`: its level clamped to the model's
/// coarsest, or the table's impostor at that resolution (none: full geometry).
Representation uniform_rep(const Uniform& u, std::size_t m, GlSceneObjects& set,
                           const std::vector<QualityTable>& tables) {
  if (u.kind == ObjectKind::kMesh)
    return {ObjectKind::kMesh, std::min(u.level_or_res, int(set.model(m).chain().size()) - 1), 0,
            0};
  for (const RepresentationQuality& r : tables[m].representations)
    if (r.rep.kind == u.kind && r.rep.resolution == u.level_or_res) return r.rep;
  return {};
}

using ItemGroups = std::vector<std::pair<std::string, std::vector<Item>>>;

/// The groups a checkpoint's instances are drawn in: by on-screen size (px
/// at the base image size, `scale` the image's multiple of it), by model,
/// and all ("all" last).
ItemGroups diagnosis_groups(const GlSceneObjects& set, const std::vector<Item>& all, int scale) {
  const std::vector<double> edges = {0, 4, 8, 16, 32, 64, 1e9};
  ItemGroups groups;
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
  return groups;
}

/// What diagnose_group draws at: the condition, the checkpoint and the
/// terrain alone there.
struct DiagnosisSpot {
  DiagnosisCondition condition;
  const PathCheckpoint& checkpoint;
  const Camera& camera;
  const Shot& bare;
};

using Interpolators = std::vector<std::map<RepKey, QualityInterpolator>>;

/// What the diagnosis predicts with: the uniform representations it tries
/// and the tables' interpolators (in context: empty unless measured).
struct DiagnosisTables {
  std::vector<Uniform> uniforms;
  Interpolators interp, interp_context;
};

/// One group drawn at full geometry and at each uniform representation:
/// a row per representation (appended to `out`, and printed on stderr).
void diagnose_group(const QualityDiagnosisInput& in, Shooter& shooter, const DiagnosisSpot& at,
                    const std::string& bucket, const std::vector<Item>& items,
                    const DiagnosisTables& t, std::vector<DiagnosisRow>& out) {
  const std::string condition = diagnosis_condition_name(at.condition);
  const std::string& cp = at.checkpoint.name;
  const bool every = bucket == "all";
  AssignedObjects full(in.set, items, [](std::size_t) { return Representation{}; });
  const Shot ref = shooter.shoot(full, at.camera, every ? 3 : 1);
  if (every && !in.image_dir.empty())
    save_png(ref.color, fmt::format("{}/{}_{}_full.png", in.image_dir, condition, cp));
  double theta = 0, size = 0, wsum = 0;
  for (const Item& it : items) {
    theta += it.view.pixels * it.view.theta_deg;
    size += it.view.pixels * it.view.size_px;
    wsum += it.view.pixels;
  }
  for (const Uniform& u : t.uniforms) {
    const auto rep_of = [&](std::size_t m) { return uniform_rep(u, m, in.set, in.tables); };
    AssignedObjects test_objects(in.set, items, rep_of);
    const Shot test = shooter.shoot(test_objects, at.camera, every ? 3 : 1);
    if (every && !in.image_dir.empty()) {
      std::string label = u.label();
      std::replace(label.begin(), label.end(), ' ', '_');
      save_png(test.color, fmt::format("{}/{}_{}_{}.png", in.image_dir, condition, cp, label));
    }
    const auto [measured, covered] = masked_ssim(ref, test, at.bare);
    const double predicted = predicted_ssim(items, rep_of, t.interp);
    DiagnosisRow row{at.condition,
                     cp,
                     bucket,
                     items.size(),
                     covered,
                     wsum > 0 ? theta / wsum : 0.0,
                     wsum > 0 ? size / wsum : 0.0,
                     u.label(),
                     predicted,
                     measured,
                     std::nullopt,
                     test.ms,
                     ref.ms};
    std::string in_context;
    if (in.context_tables) {
      const double p = predicted_ssim(items, rep_of, t.interp_context);
      row.predicted_context = p;
      in_context = fmt::format(" (in context {:.3f})", p);
    }
    out.push_back(row);
    fmt::print(stderr,
               "{:7} {} {:>10} n={:3} px={:6} {:14} predicted {:.3f}{} measured {:.3f} "
               "{:.1f} ms (full {:.1f})\n",
               condition, cp, bucket, items.size(), covered, u.label(), predicted, in_context,
               measured, test.ms, ref.ms);
  }
}

/// A swept scenario: its setup, the tables it selects from, its cull_px.
using SweepRun = std::tuple<HybridScenario, const std::vector<QualityTable>*, double>;

/// Each scenario as configured (at a fixed budget); from the tables as
/// measured too; and, when small instances may be left out, with every
/// instance drawn.
std::vector<SweepRun> sweep_runs(const BudgetSweepInput& in) {
  std::vector<SweepRun> runs;
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
  return runs;
}

}  // namespace

std::vector<DiagnosisRow> diagnose_hybrid_quality(const QualityDiagnosisInput& in) {
  const DiagnosisTables tables{
      diagnosis_uniforms(in.tables), interpolators(in.tables),
      in.context_tables ? interpolators(*in.context_tables) : Interpolators{}};
  std::vector<DiagnosisRow> out;
  for (const DiagnosisCondition condition : in.conditions) {
    const int scale = condition == DiagnosisCondition::kScene4 ? 4 : 1;
    const int h = in.height * scale;
    Shooter shooter(in.ground, in.width * scale, h, in.terrain_quads,
                    condition == DiagnosisCondition::kSky, in.samples);
    for (const PathCheckpoint& cp : in.checkpoints) {
      const Camera& cam = in.path[std::size_t(cp.frame)];
      const std::vector<Item> all = visible_items(in.set, cam, h);
      const std::vector<Item> none;
      AssignedObjects empty(in.set, none, [](std::size_t) { return Representation{}; });
      const Shot bare = shooter.shoot(empty, cam);
      for (const auto& [bucket, items] : diagnosis_groups(in.set, all, scale))
        if (!items.empty())
          diagnose_group(in, shooter, {condition, cp, cam, bare}, bucket, items, tables, out);
    }
  }
  return out;
}

std::vector<ContextCalibration> calibrate_tables_in_context(const QualityContextInput& in,
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
  std::vector<ContextCalibration> report;
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
      report.push_back({set.layout_model(m).name, rq.rep.kind, rq.rep.level, rq.rep.resolution,
                        scale, w > 0 ? p / w : 1.0, w > 0 ? q / w : 1.0, w});
    }
  return report;
}

std::vector<BudgetSweepRow> quality_budget_sweep(const BudgetSweepInput& in) {
  std::vector<BudgetSweepRow> out;
  Shooter shooter(in.ground, in.width, in.height, in.terrain_quads, false, in.samples);
  // The budget fractions are of full geometry's predicted time.
  const HybridScenario full_scenario = walk_scenario(WalkScenario::kFull, false);
  HybridOptions o = in.options;
  o.use_hysteresis = false;
  const std::vector<SweepRun> runs = sweep_runs(in);
  for (const PathCheckpoint& cp : in.checkpoints) {
    const Camera& cam = in.path[std::size_t(cp.frame)];
    const std::vector<Item> none;
    AssignedObjects empty(in.set, none, [](std::size_t) { return Representation{}; });
    const Shot bare = shooter.shoot(empty, cam, 3);
    HybridObjects full(in.set, in.tables, in.cost, full_scenario, o);
    const Shot ref = shooter.shoot(full, cam, 3);
    const double full_predicted = full.last().predicted_ms;
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
        out.push_back({cp.name, sc.name, f, o.target_ms, st.predicted_ms, test.ms, ref.ms,
                       full_predicted, bare.ms, st.expected_ssim, measured, whole,
                       st.triangles, st.instances_by_kind, std::nullopt});
        fmt::print(stderr,
                   "{} {:34} budget {:.2f} x full ({:6.1f} ms): predicted {:6.1f} ms, measured "
                   "{:6.1f} ms (full {:6.1f}, terrain {:5.1f}); expected SSIM {:.3f}, objects "
                   "{:.3f}, whole {:.4f}; mesh/relief/octahedral {}/{}/{}\n",
                   cp.name, sc.name, f, o.target_ms, st.predicted_ms, test.ms, ref.ms, bare.ms,
                   st.expected_ssim, measured, whole, st.instances_by_kind[0],
                   st.instances_by_kind[1], st.instances_by_kind[2]);
        if (in.cost_split_rounds > 0) {
          const HybridFrameStats drawn = st;  // the draws below select again
          std::vector<CostSplitRow> split =
              cost_split(shooter, objects, cam, drawn, in.cost_split_rounds);
          for (const CostSplitRow& k : split)
            fmt::print(stderr,
                       "  {:10} x {:3} in {:2} calls: predicted {:6.2f} ms, alone {:6.2f} ms, in "
                       "the frame {:6.2f} ms\n",
                       object_kind_name(k.kind), k.instances, k.draw_calls, k.predicted_ms,
                       k.alone_ms, k.in_frame_ms);
          out.back().cost_split = std::move(split);
        }
      }
  }
  return out;
}

}  // namespace terrasprite::hybrid_bench
