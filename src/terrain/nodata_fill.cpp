// SPDX-License-Identifier: MIT
// Nodata filling: each wave gives every hole cell that touches valid cells
// the mean of those neighbours, so voids close from their rims inwards
// without inventing slopes.
#include <fmt/format.h>

#include "terrasprite/error.h"
#include "terrasprite/terrain_gen.h"

namespace terrasprite {

long long fill_nodata(std::span<float> h, std::span<std::uint8_t> valid, int width, int height) {
  std::vector<int> holes;
  for (int p = 0; p < width * height; ++p)
    if (!valid[p]) holes.push_back(p);
  if (holes.empty()) return 0;
  if (holes.size() == static_cast<std::size_t>(width) * height)
    throw InputError("all cells are nodata");
  const long long filled = static_cast<long long>(holes.size());
  std::vector<int> next;
  std::vector<std::pair<int, float>> wave;
  while (!holes.empty()) {
    wave.clear();
    next.clear();
    for (int p : holes) {
      int x = p % width, y = p / width;
      double sum = 0;
      int n = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          int nx = x + dx, ny = y + dy;
          if ((dx || dy) && nx >= 0 && ny >= 0 && nx < width && ny < height &&
              valid[ny * width + nx]) {
            sum += h[ny * width + nx];
            ++n;
          }
        }
      if (n)
        wave.emplace_back(p, float(sum / n));
      else
        next.push_back(p);
    }
    for (auto [p, v] : wave) {
      h[p] = v;
      valid[p] = 1;
    }
    holes.swap(next);
  }
  return filled;
}

}  // namespace terrasprite
