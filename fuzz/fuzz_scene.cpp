// SPDX-License-Identifier: MIT
// Fuzz target: the scene file parser (models, listed instances, scatters)
// over a small terrain. Bad input must end in InputError. Scatters of more
// than 10,000 instances are skipped: their cost is linear in the count and a
// million would spend the fuzzer's time on one input.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "terrasprite/common/error.h"
#include "terrasprite/objects/object_layout.h"
#include "terrasprite/terrain/synth.h"

namespace {

bool large_count(const nlohmann::json& o) {
  if (!o.is_object() || !o.contains("count") || !o["count"].is_number()) return false;
  return !(o["count"].get<double>() <= 10000);
}

bool skipped(const std::string& text) {
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  if (!j.is_object()) return false;
  if (j.contains("scatter_defaults") && large_count(j["scatter_defaults"])) return true;
  if (j.contains("scatter") && j["scatter"].is_array())
    for (const auto& s : j["scatter"])
      if (large_count(s)) return true;
  return false;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const terrasprite::Heightfield terrain = [] {
    terrasprite::SynthOptions s;
    s.size = 33;
    return terrasprite::synthesize_terrain(s);
  }();
  const std::string text(reinterpret_cast<const char*>(data), size);
  if (skipped(text)) return 0;
  try {
    terrasprite::parse_object_layout(text, "fuzz.json", "/nonexistent", terrain);
  } catch (const terrasprite::InputError&) {
  }
  return 0;
}
