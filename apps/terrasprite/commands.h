// SPDX-License-Identifier: MIT
// Each sub-command registers itself on the app; main.cpp lists them in the
// order of the pipeline they show.
#pragma once
#include <CLI/CLI.hpp>

namespace terrasprite::cli {

void add_info(CLI::App& app);
void add_render(CLI::App& app);
void add_compare(CLI::App& app);
/// `tile`: a terrain to Cloud-Optimized GeoTIFFs of its pyramid, for streaming.
void add_tile(CLI::App& app);
void add_demo(CLI::App& app);
/// `objects info|table`: an object model, its representations and quality tables.
void add_objects(CLI::App& app);
#ifdef TS_HAVE_VIEWER
void add_view(CLI::App& app);
#endif
/// `bench` groups the benchmarks; each adds itself under it.
void add_bench(CLI::App& app);

}  // namespace terrasprite::cli
