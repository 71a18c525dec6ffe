// SPDX-License-Identifier: MIT
// Where a sphere's silhouette lies along one image axis, shared by the
// occlusion test's screen rectangle and the instances' covered pixels.
#pragma once
#include <cmath>
#include <utility>

namespace terrasprite {

/// Extreme slopes a = u / z of the lines through the eye tangent to a circle
/// at (u, z), z > r, radius r: the roots of a^2 (z^2 - r^2) - 2 a u z +
/// u^2 - r^2 = 0. A plane through the eye that holds the other image axis is
/// tangent to the sphere exactly when its line is tangent to this circle.
inline std::pair<double, double> tangent_slopes(double u, double z, double r) {
  const double root = r * std::sqrt(u * u + z * z - r * r);
  const double den = z * z - r * r;
  return {(u * z - root) / den, (u * z + root) / den};
}

}  // namespace terrasprite
