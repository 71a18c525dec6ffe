// SPDX-License-Identifier: MIT
// The process's own memory, for long runs: resident set size now and at
// peak, and handing freed heap pages back to the operating system.
#pragma once
#include <utility>
#include <vector>

namespace terrasprite {

/// Resident set size now, MiB (/proc/self/statm); 0 where it cannot be read.
double resident_mb();

/// Peak resident set size of this process so far, MiB (getrusage).
double peak_resident_mb();

/// Returns free heap pages to the OS (glibc malloc_trim). Why: llvmpipe
/// allocates tens of MB in small blocks during a full-resolution draw and
/// frees them; glibc keeps those pages, so a long run's RSS climbs in steps to
/// its worst frame's scratch and stays there. Returns the call's wall ms;
/// a no-op (0) on other C libraries.
double release_free_heap();

/// RSS sampled along a run, and the growth a soak is judged by.
struct MemoryCurve {
  std::vector<std::pair<int, double>> samples;  ///< (frames done, RSS MiB)
  double trim_ms = 0;                           ///< release_free_heap() time in all
  /// Least-squares slope of RSS over frames >= `after`, in MiB per 10,000
  /// frames; 0 with fewer than two such samples.
  double growth_per_10k(int after) const;
};

}  // namespace terrasprite
