// SPDX-License-Identifier: MIT
// The one JSON writer of reports: typed results are turned into JSON by each
// study's report code and written here, atomically, with a "generator" key.
#pragma once
#include <nlohmann/json_fwd.hpp>
#include <string>

#include "terrasprite/output/output_file.h"

namespace terrasprite::report {

/// Writes pretty JSON (an object gets a "generator" key: terrasprite and its
/// version) to a temporary name beside `path`, renamed into place when
/// complete. An existing file is replaced only if terrasprite wrote it or
/// `policy.overwrite` is set. Throws InputError naming the file on failure.
void write_json(const nlohmann::json& j, const std::string& path, const OutputPolicy& policy);

/// A measured figure: `v`, or null where it is NaN or infinite (not measured,
/// no samples).
nlohmann::json number_or_null(double v);

}  // namespace terrasprite::report
