// SPDX-License-Identifier: MIT
// LOD chain: triangle counts strictly fall, errors rise, the coarsest level
// still spans the object within its error.
#include "terrasprite/objects/lod_chain.h"

#include <gtest/gtest.h>

#include "terrasprite/objects/model.h"
#include "test_util.h"

namespace ts = terrasprite;

namespace {

void check_chain(const ts::Model& m, const std::vector<ts::LodLevel>& chain) {
  ASSERT_GE(chain.size(), 4u) << m.name;
  EXPECT_EQ(chain[0].triangles(), m.triangles());
  EXPECT_EQ(chain[0].error_m, 0.0);
  for (std::size_t i = 1; i < chain.size(); ++i) {
    EXPECT_LT(chain[i].triangles(), chain[i - 1].triangles()) << m.name << " level " << i;
    EXPECT_GE(chain[i].error_m, chain[i - 1].error_m) << m.name << " level " << i;
    for (std::uint32_t v : chain[i].indices) ASSERT_LT(v, chain[i].positions.size());
    std::uint32_t covered = 0;
    for (const ts::MeshPart& p : chain[i].parts) covered += p.index_count;
    EXPECT_EQ(covered, chain[i].indices.size());
  }
  EXPECT_GT(chain.back().error_m, 0.0);
  EXPECT_LE(chain.back().triangles(), std::max<std::size_t>(8, m.triangles() / 50)) << m.name;
  // The coarsest level's bounding box matches the full one within its error.
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  for (std::uint32_t v : chain.back().indices) {
    lo = glm::min(lo, chain.back().positions[v]);
    hi = glm::max(hi, chain.back().positions[v]);
  }
  const float tol = float(chain.back().error_m) + 1e-4f;
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(lo[k], m.bounds_min[k], tol) << m.name << " axis " << k;
    EXPECT_NEAR(hi[k], m.bounds_max[k], tol) << m.name << " axis " << k;
  }
}

}  // namespace

TEST(LodChain, ScansAndKits) {
  const std::string data = tstest::shared_data();
  if (data.empty()) GTEST_SKIP() << "../shared/data is absent";
  for (const char* f : {"/models_scans/teapot.obj", "/models_scans/spot.obj",
                        "/models_kenney_racing/decoration-forest.glb",
                        "/models_cesium_milk_truck/CesiumMilkTruck.glb"}) {
    ts::ModelOptions o;
    o.height_m = 2.0;
    const ts::Model m = ts::load_model(data + f, o);
    check_chain(m, ts::build_lod_chain(m));
  }
}
