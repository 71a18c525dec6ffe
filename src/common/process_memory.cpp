// SPDX-License-Identifier: MIT
#include "terrasprite/common/process_memory.h"

#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace terrasprite {

double resident_mb() {
  std::FILE* f = std::fopen("/proc/self/statm", "r");
  if (!f) return 0;
  long pages_total = 0, pages_resident = 0;
  const int n = std::fscanf(f, "%ld %ld", &pages_total, &pages_resident);
  std::fclose(f);
  if (n != 2) return 0;
  return double(pages_resident) * double(sysconf(_SC_PAGESIZE)) / (1 << 20);
}

double peak_resident_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_maxrss) / 1024.0;  // kilobytes on Linux
}

double release_free_heap() {
#if defined(__GLIBC__)
  const auto t0 = std::chrono::steady_clock::now();
  malloc_trim(0);
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
#else
  return 0;
#endif
}

double MemoryCurve::growth_per_10k(int after) const {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (auto [frame, mb] : samples) {
    if (frame < after) continue;
    n += 1;
    sx += frame;
    sy += mb;
    sxx += double(frame) * frame;
    sxy += frame * mb;
  }
  const double den = n * sxx - sx * sx;
  if (n < 2 || den <= 0) return 0;
  return (n * sxy - sx * sy) / den * 10000.0;
}

}  // namespace terrasprite
