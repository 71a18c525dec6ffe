// SPDX-License-Identifier: MIT
// Each sub-command registers itself on the app; main.cpp lists them in the
// order of the pipeline they show. `policy` (the run's --overwrite) is kept by
// reference and read when the command runs, after the whole command line is
// parsed: it must outlive app.parse().
#pragma once
#include <CLI/CLI.hpp>

#include "terrasprite/output/output_file.h"

namespace terrasprite::cli {

void add_info(CLI::App& app, const OutputPolicy& policy);
void add_render(CLI::App& app, const OutputPolicy& policy);
void add_compare(CLI::App& app, const OutputPolicy& policy);
/// `tile`: a terrain to Cloud-Optimized GeoTIFFs of its pyramid, for streaming.
void add_tile(CLI::App& app, const OutputPolicy& policy);
void add_demo(CLI::App& app, const OutputPolicy& policy);
/// `objects info|table`: an object model, its representations and quality tables.
void add_objects(CLI::App& app, const OutputPolicy& policy);
#ifdef TS_HAVE_VIEWER
void add_view(CLI::App& app, const OutputPolicy& policy);
#endif
/// `bench` groups the benchmarks; each adds itself under it.
void add_bench(CLI::App& app, const OutputPolicy& policy);

}  // namespace terrasprite::cli
