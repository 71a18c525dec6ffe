// SPDX-License-Identifier: MIT
// llvmpipe's rasteriser threads for a benchmark's process (Mesa's LP_NUM_THREADS).
#pragma once
#include <optional>
#include <string>

namespace terrasprite::cli {

/// Applies `--llvmpipe-threads` (`option` names it in errors). Must run
/// before the process's first GL context: llvmpipe reads LP_NUM_THREADS
/// once, when EGL is initialised; other drivers ignore it. `setting`:
/// - a count 0-32: that many rasteriser threads; 0 rasterises on the
///   thread that draws;
/// - "driver": LP_NUM_THREADS as the environment has it (unset: llvmpipe's
///   default, one thread per core);
/// - "auto": as the environment has it when it is set; else 0 on a machine
///   with at most two hardware threads (there llvmpipe's threads and the
///   drawing thread contend for the cores), the driver's default on more.
/// Returns LP_NUM_THREADS as it then stands (nullopt: unset). Throws
/// InputError naming the option for any other setting.
std::optional<std::string> apply_llvmpipe_threads(const std::string& setting, const char* option);

}  // namespace terrasprite::cli
