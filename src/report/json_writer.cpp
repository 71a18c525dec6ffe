// SPDX-License-Identifier: MIT
#include "terrasprite/report/json_writer.h"

#include <cmath>
#include <nlohmann/json.hpp>

namespace terrasprite::report {

void write_json(const nlohmann::json& j, const std::string& path, const OutputPolicy& policy) {
  if (!j.is_object()) {
    write_output_file(path, policy, j.dump(2) + "\n");
    return;
  }
  nlohmann::json with_generator = j;
  with_generator["generator"] = generator_name();
  write_output_file(path, policy, with_generator.dump(2) + "\n");
}

nlohmann::json number_or_null(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

}  // namespace terrasprite::report
