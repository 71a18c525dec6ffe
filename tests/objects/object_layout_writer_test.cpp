// SPDX-License-Identifier: MIT
// Placed instances written as a scene file read back to the same instances.
#include "terrasprite/objects/object_layout_writer.h"

#include <gtest/gtest.h>

#include "terrasprite/objects/object_layout.h"

using namespace terrasprite;

TEST(ObjectLayoutWriter, ScatteredInstancesRoundTripAsListedOnes) {
  Heightfield h;
  h.width = h.height = 33;
  h.spacing_x = h.spacing_y = 10;
  h.heights.resize(33 * 33);
  for (int j = 0; j < 33; ++j)
    for (int i = 0; i < 33; ++i) h.at(i, j) = float(i + 0.5 * j);
  const ObjectLayout a = parse_object_layout(R"({
      "models": [{"name": "pot", "file": "pot.obj", "height_m": 4, "color": [0.5, 0.6, 0.7],
                  "double_sided": false},
                 {"name": "cow", "file": "cow.obj", "up": "z", "texture": "cow.png"}],
      "instances": [{"model": "cow", "position": [10, -20], "heading_deg": 30, "scale": 2}],
      "scatter": [{"model": "pot", "count": 12, "seed": 3, "min_spacing_m": 5}]})",
                                             "s.json", "/models", h);
  const ObjectLayout b = parse_object_layout(object_layout_json(a), "placed.json", "/elsewhere", h);
  ASSERT_EQ(b.instances.size(), a.instances.size());
  for (std::size_t k = 0; k < a.instances.size(); ++k) {
    EXPECT_EQ(b.instances[k].model, a.instances[k].model);
    EXPECT_EQ(b.instances[k].instance.position, a.instances[k].instance.position);
    EXPECT_EQ(b.instances[k].instance.heading_deg, a.instances[k].instance.heading_deg);
    EXPECT_EQ(b.instances[k].instance.scale, a.instances[k].instance.scale);
    EXPECT_FALSE(b.instances[k].grounded);  // absolute [x, y, z]
  }
  EXPECT_EQ(b.models[0].file, "/models/pot.obj");
  EXPECT_EQ(b.models[1].options.texture, "/models/cow.png");
  EXPECT_EQ(b.models[1].options.up, UpAxis::kZ);
  EXPECT_EQ(b.models[0].options.double_sided, std::optional<bool>(false));
  EXPECT_FLOAT_EQ(b.models[0].options.color.g, 0.6f);
}
