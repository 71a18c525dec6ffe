// SPDX-License-Identifier: MIT
// HybridObjects end to end on a model made in code (a 6-triangle tower): one
// near instance, twelve far and tiny; under a budget below the floor the tiny
// ones are left out (HybridOptions::cull_px), never the near one, and with
// room in the budget nothing is. GL (llvmpipe), about 0.1 s.
#include "terrasprite/hybrid_objects.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "gl/render_target.h"
#include "objects/object_test_util.h"
#include "terrasprite/gl_context.h"
#include "terrasprite/instance_view.h"
#include "terrasprite/object_scene.h"
#include "terrasprite/object_set.h"
#include "test_util.h"

namespace ts = terrasprite;

namespace {

constexpr int kW = 160, kH = 90, kTiny = 12;

// The near tower at the origin (30 m); the tiny ones 3 cm tall around it.
std::string tower_instances() {
  std::string instances = R"([{"model": "t", "position": [0, 0]})";
  for (int i = 0; i < kTiny; ++i)
    instances += R"(, {"model": "t", "scale": 0.001, "position": [)" + std::to_string(-30 + 5 * i) +
                 ", " + std::to_string(20 - 3 * i) + "]}";
  return instances + "]";
}

struct World : tstest::TowerWorld {
  World() : TowerWorld(R"("height_m": 30, "color": [1, 0, 0])", tower_instances()) {}
};

ts::Camera view(const ts::Terrain& t) {
  const glm::dvec3 target(0, 0, t.heights.sample(0, 0) + 10);
  return tstest::orbit(target, 300, 20, 15, 50, double(kW) / kH);
}

/// Draws the objects once under a fixed budget (ms, whole frame, terrain term 0).
ts::HybridFrameStats draw_once(World& w, double budget_ms, double cull_px) {
  ts::ObjectSet set(w.objects);
  ts::DrawCostModel cost;
  cost.set_terms(ts::ObjectKind::kMesh, {0.01, 0.05, 1e-4, 1e-6});
  cost.set_frame_ms(0);
  ts::HybridOptions o;
  o.width = kW;
  o.height = kH;
  o.target_ms = budget_ms;
  o.cull_px = cull_px;
  ts::HybridObjects objects(set, {}, cost,
                            {"pm",
                             {ts::ObjectKind::kMesh},
                             ts::SelectionPolicy::kGreedy,
                             false,
                             ts::HybridScenario::Control::kFixed},
                            o);
  ts::gl::RenderTarget target(kW, kH);
  target.bind_and_clear();
  objects.draw(view(w.terrain));
  return objects.last();
}

TEST(HybridObjects, TinyInstancesGoUnderATightBudgetTheNearOneStays) {
  ts::GlContext ctx;
  World w;
  // The scene is as intended: every instance in view, only the first over 4 px.
  const ts::Camera cam = view(w.terrain);
  ts::ObjectSet probe(w.objects);
  const ts::Model& model = probe.model(0).model();
  const auto inst = probe.instances(0);
  ASSERT_EQ(inst.size(), std::size_t(kTiny + 1));
  for (std::size_t i = 0; i < inst.size(); ++i) {
    const ts::InstanceView v =
        ts::view_instance(cam, kH, inst[i], glm::dvec3(model.center()), model.bounding_radius());
    ASSERT_TRUE(v.visible) << i;
    if (i == 0) {
      EXPECT_GT(v.size_px, 4.0);
    } else {
      EXPECT_LT(v.size_px, 4.0) << i;
    }
  }
  // Under the floor (each instance costs about 0.06 ms at its cheapest).
  const ts::HybridFrameStats starved = draw_once(w, 0.001, 4.0);
  EXPECT_EQ(starved.visible, kTiny + 1);
  EXPECT_EQ(starved.not_drawn, kTiny);
  EXPECT_EQ(starved.instances_by_kind[0], 1);
  EXPECT_EQ(starved.triangles, 6);
  // Without the option every visible instance is drawn, over budget or not.
  const ts::HybridFrameStats all = draw_once(w, 0.001, 0.0);
  EXPECT_EQ(all.not_drawn, 0);
  EXPECT_EQ(all.instances_by_kind[0], kTiny + 1);
  EXPECT_GT(all.floor_ms, starved.floor_ms);
  // Room for all: none left out.
  const ts::HybridFrameStats room = draw_once(w, 100.0, 4.0);
  EXPECT_EQ(room.not_drawn, 0);
  EXPECT_EQ(room.instances_by_kind[0], kTiny + 1);
}

}  // namespace
