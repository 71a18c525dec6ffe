// SPDX-License-Identifier: MIT
// A quality table as JSON, both ways: the document `objects table` writes
// (table.json) and the format of the table cache (quality_table_cache.h).
#pragma once
#include <nlohmann/json_fwd.hpp>

#include "terrasprite/objects/quality_table.h"

namespace terrasprite {

/// The format version written under "format"; a cached table of another
/// version is measured again.
extern const char* const kQualityTableFormat;

/// The table as the JSON contract has it: format, model, triangles,
/// build_ms, options (kinds, resolutions, sizes_px, angle_step_deg,
/// full_sphere, headings_deg, views), representations (each with its cost
/// per size and its samples; an infinite PSNR written as "inf", an
/// unmeasured score as null) and table (Table 1's cells).
nlohmann::json table_json(const QualityTable& t, const TableOptions& o);

/// Reads back what table_json wrote (for the cache). Throws InputError on a
/// document of another format version or without the expected shape.
QualityTable table_from_json(const nlohmann::json& j);

}  // namespace terrasprite
