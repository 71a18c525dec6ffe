// SPDX-License-Identifier: MIT
// A quality table as JSON, both ways.
#include "terrasprite/objects/quality_table_json.h"

#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "terrasprite/common/error.h"

namespace terrasprite {

// Raised whenever what a table measures changes (levels, impostors, views),
// so that tables cached before are measured again.
const char* const kQualityTableFormat = "terrasprite-objects-table-6";

namespace {

// Infinite PSNR (identical images) is written as the string "inf": JSON has
// no infinity. A score that could not be measured (NaN) is null, read back
// as NaN, which the interpolator skips: a table holding one must still load.
nlohmann::json number(double v) {
  if (std::isnan(v)) return nullptr;
  return std::isinf(v) ? nlohmann::json("inf") : nlohmann::json(v);
}
double number(const nlohmann::json& v) {
  if (v.is_null()) return NAN;
  return v.is_string() && v == "inf" ? INFINITY : v.get<double>();
}

}  // namespace

nlohmann::json table_json(const QualityTable& t, const TableOptions& o) {
  nlohmann::json reps = nlohmann::json::array();
  for (const RepresentationQuality& q : t.representations) {
    nlohmann::json r = {{"kind", object_kind_name(q.rep.kind)},
                        {"triangles", q.triangles},
                        {"bytes", q.bytes},
                        {"ms_per_instance", q.ms_per_instance},
                        {"build_ms", q.build_ms}};
    if (q.rep.kind == ObjectKind::kMesh) {
      r["level"] = q.rep.level;
      r["error_m"] = q.error_m;
    } else {
      r["resolution"] = q.rep.resolution;
    }
    if (q.rep.kind == ObjectKind::kOctahedral) r["views"] = q.rep.views;
    nlohmann::json cost = nlohmann::json::array(), samples = nlohmann::json::array();
    for (const SizeCost& c : q.cost)
      cost.push_back({{"size_px", c.size_px}, {"ms_per_instance", c.ms_per_instance}});
    for (const QualitySample& s : q.samples)
      samples.push_back({{"phi_deg", s.phi_deg},
                         {"theta_deg", s.theta_deg},
                         {"size_px", s.size_px},
                         {"psnr", number(s.psnr)},
                         {"ssim", number(s.ssim)},
                         {"heading_deg", s.heading_deg}});
    r["cost"] = cost;
    r["samples"] = samples;
    reps.push_back(r);
  }
  nlohmann::json table = nlohmann::json::array();
  for (const TableEntry& e : t.table) {
    nlohmann::json row = {{"kind", object_kind_name(e.kind)},
                          {"size_px", e.size_px},
                          {"metric", e.metric},
                          {"target", e.target}};
    row[e.kind == ObjectKind::kMesh ? "level" : "resolution"] =
        e.choice ? nlohmann::json(*e.choice) : nlohmann::json(nullptr);
    table.push_back(row);
  }
  std::vector<std::string> kinds;
  for (ObjectKind k : o.kinds) kinds.push_back(object_kind_name(k));
  return {{"format", kQualityTableFormat},
          {"model", t.model},
          {"triangles", t.triangles},
          {"build_ms", t.build_ms},
          {"options",
           {{"kinds", kinds},
            {"resolutions", o.resolutions},
            {"sizes_px", o.sizes_px},
            {"angle_step_deg", o.angle_step_deg},
            {"full_sphere", o.full_sphere},
            {"headings_deg", o.headings_deg},
            {"views", o.views}}},
          {"representations", reps},
          {"table", table}};
}

QualityTable table_from_json(const nlohmann::json& j) {
  try {
    if (j.at("format") != kQualityTableFormat) throw InputError("cached table has another format version");
    QualityTable t;
    t.model = j.at("model");
    t.triangles = j.at("triangles");
    t.build_ms = j.at("build_ms");
    for (const auto& r : j.at("representations")) {
      RepresentationQuality q;
      q.rep.kind = parse_object_kind(r.at("kind"), "cache");
      q.rep.level = r.value("level", 0);
      q.rep.resolution = r.value("resolution", 0);
      q.rep.views = r.value("views", 0);
      q.triangles = r.at("triangles");
      q.bytes = r.at("bytes");
      q.ms_per_instance = r.at("ms_per_instance");
      q.build_ms = r.at("build_ms");
      q.error_m = r.value("error_m", 0.0);
      for (const auto& c : r.at("cost"))
        q.cost.push_back({c.at("size_px"), c.at("ms_per_instance")});
      for (const auto& s : r.at("samples"))
        q.samples.push_back({s.at("phi_deg"), s.at("theta_deg"), s.at("size_px"),
                             number(s.at("psnr")), number(s.at("ssim")),
                             s.value("heading_deg", 0.0)});
      t.representations.push_back(std::move(q));
    }
    for (const auto& e : j.at("table")) {
      TableEntry row{parse_object_kind(e.at("kind"), "cache"), e.at("size_px"), e.at("metric"),
                     e.at("target"), std::nullopt};
      const auto& c = row.kind == ObjectKind::kMesh ? e.at("level") : e.at("resolution");
      if (!c.is_null()) row.choice = c.get<int>();
      t.table.push_back(row);
    }
    return t;
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("cached table: {}", e.what()));
  }
}

}  // namespace terrasprite
