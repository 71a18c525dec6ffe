// SPDX-License-Identifier: MIT
#include <gtest/gtest.h>

#include "terrasprite/error.h"
#include "terrasprite/walkthrough_path.h"

namespace terrasprite {
namespace {

constexpr const char* kPath =
    R"({"keyframes": [{"t": 1, "position": [0, 0, 5]}, {"t": 11, "position": [9, 0, 5]}],
  "checkpoints": [{"name": "A", "t": 1}, {"name": "B", "t": 6}, {"name": "C", "t": 11}]})";

TEST(Walkthrough, CheckpointsLandOnTheirFrames) {
  const auto cps = checkpoints_of(kPath, "p.json", 21);
  ASSERT_EQ(cps.size(), 3u);
  EXPECT_EQ(cps[0].frame, 0);
  EXPECT_EQ(cps[1].frame, 10);
  EXPECT_EQ(cps[2].frame, 20);
  EXPECT_TRUE(checkpoints_of(R"({"keyframes": []})", "p.json", 5).empty());
}

TEST(Walkthrough, BadCheckpointsNameTheFile) {
  for (const char* bad :
       {R"({"keyframes": [{"t": 0}, {"t": 1}], "checkpoints": [{"t": 0.5}]})",
        R"({"keyframes": [{"t": 0}, {"t": 1}], "checkpoints": [{"name": "A", "t": 2}]})",
        R"({"keyframes": [{"t": 0}, {"t": 1}], "checkpoints": [{"name": "A", "t": "x"}]})",
        R"({"keyframes": [{"t": 0}, {"t": 1}], "checkpoints": 3})"}) {
    try {
      checkpoints_of(bad, "p.json", 5);
      ADD_FAILURE() << bad;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("p.json"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace terrasprite
