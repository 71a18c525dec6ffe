// SPDX-License-Identifier: MIT
// objects table's report text: Table 1's Markdown and the warnings for
// options that would make a figure degenerate. No GL; well under a second.
#include "terrasprite/report/objects_report.h"

#include <gtest/gtest.h>

#include <sstream>

namespace terrasprite {
namespace {

TEST(ObjectsReport, TableOneHasASeparatorCellForEveryColumn) {
  TableOptions o;
  o.kinds = {ObjectKind::kRelief};
  o.sizes_px = {100};
  o.ssim_targets = {0.9, 0.95, 0.98, 0.99};
  o.psnr_targets = {20, 30};
  QualityTable t;
  t.model = "m";
  std::istringstream md(report::table1_markdown(t, o));
  int tables = 0;
  std::string header;
  for (std::string line; std::getline(md, line);) {
    if (line.rfind("|---", 0) != 0) {
      header = line;
      continue;
    }
    ++tables;
    const auto cells = [](const std::string& s) { return std::count(s.begin(), s.end(), '|'); };
    EXPECT_EQ(cells(line), cells(header)) << header << "\n" << line;
  }
  EXPECT_EQ(tables, 2);
}

TEST(ObjectsReport, WarnsOfTooFewViewsAndOfASingleSize) {
  TableOptions o;
  EXPECT_TRUE(report::objects_report_warnings(o).empty());
  o.angle_step_deg = 60;
  ASSERT_EQ(report::objects_report_warnings(o).size(), 1u);
  EXPECT_NE(report::objects_report_warnings(o)[0].find("--angle-step 60"), std::string::npos);
  o.angle_step_deg = 30;
  o.sizes_px = {100, 100};
  ASSERT_EQ(report::objects_report_warnings(o).size(), 1u);
  EXPECT_NE(report::objects_report_warnings(o)[0].find("one size"), std::string::npos);
}

}  // namespace
}  // namespace terrasprite
