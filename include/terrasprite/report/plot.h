// SPDX-License-Identifier: MIT
// The one plot runner: gnuplot on a script in an output directory, and the
// text writer for its data, scripts and report pages.
#pragma once
#include <string>

namespace terrasprite::report {

/// Runs `gnuplot SCRIPT` inside `dir`, its output in `dir`/gnuplot.log.
/// Returns an empty string on success, else one line saying what failed
/// (gnuplot missing, or its exit status and first error line), which the
/// caller reports; a failed plot never fails the run (the .dat files stay).
std::string run_gnuplot(const std::string& dir, const std::string& script);

/// Writes `text` to `path` (a file inside an output directory being built);
/// throws InputError naming the path when it cannot be written.
void write_text(const std::string& path, const std::string& text);

}  // namespace terrasprite::report
