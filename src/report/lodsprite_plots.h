// SPDX-License-Identifier: MIT
// The figures of a `bench lodsprite` report (lodsprite_report.cpp writes the page).
#pragma once
#include <string>
#include <vector>

#include "terrasprite/experiment/lodsprite/lodsprite_result.h"
#include "terrasprite/output/output_dir.h"

namespace terrasprite::report::detail {

/// The plots a run has data for, in the page's order.
std::vector<const char*> plot_files(const lodsprite::LodspriteResult& j);

/// The per-frame and sweep data gnuplot reads, one header row of column names each.
void write_plot_data(const lodsprite::LodspriteResult& j, OutputDir& out);

/// Writes plots.gp and runs gnuplot; returns its error line, empty on success.
std::string draw_plots(const lodsprite::LodspriteResult& j, OutputDir& out);

/// The same-frame figures' images: full, LOD, sprite and both differences.
void save_figures(const lodsprite::LodspriteResult& j, OutputDir& out);

}  // namespace terrasprite::report::detail
