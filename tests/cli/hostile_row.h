// SPDX-License-Identifier: MIT
// One row of a hostile-input table, run in a working directory of the user's
// files: exit status 2, one line naming the problem, nothing written or removed.
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <string>

#include "test_util.h"

namespace tstest {

/// Runs `args` in `work` and expects the refusal: status 2, exactly one line
/// holding `fragment`, and `work` as `before` (tstest::snapshot) found it.
/// Returns the run for further checks.
inline CliResult expect_refused_untouched(const std::filesystem::path& work,
                                          const std::string& args, const std::string& fragment,
                                          const std::map<std::string, std::string>& before) {
  const CliResult r = run_cli_in(work.string(), args);
  EXPECT_EQ(r.status, 2) << args << "\n" << r.output;
  EXPECT_NE(r.output.find(fragment), std::string::npos) << args << "\n" << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << args << "\n" << r.output;
  EXPECT_EQ(snapshot(work), before) << args << ": the working directory changed";
  return r;
}

}  // namespace tstest
