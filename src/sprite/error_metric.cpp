// SPDX-License-Identifier: MIT
// The LOD-sprite error metric: Chen, Swan, Kuo, Kaufman, "LOD-Sprite Technique
// for Accelerated Terrain Rendering", IEEE Visualization 1999, section 3.2:
// Eq. (1), the angle by which the coarse surface displaces a full-resolution
// vertex C to C' as seen from the new eye, and Eq. (2), a new keyframe when
// the mean squared error (in pixels) exceeds the squared threshold.
#include <algorithm>
#include <atomic>
#include <cassert>
#include <cmath>
#include <limits>

#include "terrasprite/sprite/error_metric.h"
#include "terrasprite/terrain/grid_mesh.h"
#include "terrasprite/terrain/pyramid.h"

namespace terrasprite {
namespace {

// Moller-Trumbore; returns the ray parameter or NaN for a miss.
double ray_triangle(glm::dvec3 o, glm::dvec3 d, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
  const glm::dvec3 e1 = b - a, e2 = c - a, p = glm::cross(d, e2);
  const double det = glm::dot(e1, p);
  if (std::abs(det) < 1e-12) return std::numeric_limits<double>::quiet_NaN();
  const double inv = 1.0 / det;
  const glm::dvec3 s = o - a;
  const double u = glm::dot(s, p) * inv;
  const double eps = 1e-9;
  if (u < -eps || u > 1 + eps) return std::numeric_limits<double>::quiet_NaN();
  const glm::dvec3 q = glm::cross(s, e1);
  const double v = glm::dot(d, q) * inv;
  if (v < -eps || u + v > 1 + eps) return std::numeric_limits<double>::quiet_NaN();
  return glm::dot(e2, q) * inv;
}

bool inside_image(glm::dvec2 px, int w, int h) {
  return px.x >= 0 && px.x <= w && px.y >= 0 && px.y <= h;
}

// project_to_pixel with the view-projection matrix built once per frame.
bool project(const glm::dmat4& vp, int w, int h, glm::dvec3 p, glm::dvec2& pixel) {
  const glm::dvec4 clip = vp * glm::dvec4(p, 1.0);
  if (clip.w <= 1e-12) return false;
  pixel = {(clip.x / clip.w * 0.5 + 0.5) * w, (0.5 - clip.y / clip.w * 0.5) * h};
  return true;
}

}  // namespace

double signed_edge_offset(glm::dvec3 C, glm::dvec3 a, glm::dvec3 e) {
  const glm::dvec3 ae = e - a;
  const double t = std::clamp(glm::dot(C - a, ae) / glm::dot(ae, ae), 0.0, 1.0);
  const glm::dvec3 closest = a + t * ae;
  const glm::dvec2 axy(a), ae2(ae);
  const double t2 = std::clamp(glm::dot(glm::dvec2(C) - axy, ae2) / glm::dot(ae2, ae2), 0.0, 1.0);
  const double edge_z = a.z + t2 * ae.z;
  const double dist = glm::length(C - closest);
  return C.z >= edge_z ? dist : -dist;
}

glm::dvec3 grid_normal(const Heightfield& h, int i, int j) {
  const int i0 = std::max(i - 1, 0), i1 = std::min(i + 1, h.width - 1);
  const int j0 = std::max(j - 1, 0), j1 = std::min(j + 1, h.height - 1);
  const double dzdx = i1 > i0 ? (h.at(i1, j) - h.at(i0, j)) / ((i1 - i0) * h.spacing_x) : 0.0;
  const double dzdy =
      j1 > j0 ? (h.at(i, j0) - h.at(i, j1)) / ((j1 - j0) * h.spacing_y) : 0.0;  // rows run south
  return glm::normalize(glm::dvec3(-dzdx, -dzdy, 1.0));
}

CoarseGrid make_coarse_grid(const Heightfield& h, int quads) {
  assert(h.width >= 2 && h.height >= 2);
  CoarseGrid g;
  g.xs = quad_indices(h.width, quads);
  g.ys = quad_indices(h.height, quads);
  g.quads_x = int(g.xs.size()) - 1;
  g.quads_y = int(g.ys.size()) - 1;
  for (int j : g.ys)
    for (int i : g.xs) g.vertices.emplace_back(h.world_x(i), h.world_y(j), double(h.at(i, j)));
  const std::size_t n = static_cast<std::size_t>(g.quad_count());
  g.centre.resize(n);
  g.has_centre.resize(n);
  g.edge_offset.resize(n);
  g.normal.resize(n);
  g.max_deviation.resize(n);
  for (int r = 0; r < g.quads_y; ++r)
    for (int c = 0; c < g.quads_x; ++c) {
      const std::size_t q = static_cast<std::size_t>(r) * g.quads_x + c;
      const int ci = (g.xs[c] + g.xs[c + 1]) / 2, cj = (g.ys[r] + g.ys[r + 1]) / 2;
      g.has_centre[q] = (g.xs[c + 1] - g.xs[c] >= 2 && g.ys[r + 1] - g.ys[r] >= 2) ? 1 : 0;
      const glm::dvec3 C(h.world_x(ci), h.world_y(cj), double(h.at(ci, cj)));
      g.centre[q] = C;
      // Distance from C to the diagonal edge a (NW) - e (SE) beneath it.
      const glm::dvec3 a = g.vertex(c, r), e = g.vertex(c + 1, r + 1);
      g.edge_offset[q] = signed_edge_offset(C, a, e);
      g.normal[q] = grid_normal(h, ci, cj);
      // Coarse surface over the quad: triangles (a, d, e) below the diagonal, (a, e, b) above it.
      const double za = a.z, zb = g.vertex(c + 1, r).z, zd = g.vertex(c, r + 1).z, ze = e.z;
      double dev = 0;
      for (int j = g.ys[r]; j <= g.ys[r + 1]; ++j)
        for (int i = g.xs[c]; i <= g.xs[c + 1]; ++i) {
          const double u = double(i - g.xs[c]) / (g.xs[c + 1] - g.xs[c]);
          const double v = double(j - g.ys[r]) / (g.ys[r + 1] - g.ys[r]);
          const double z =
              v >= u ? za + v * (zd - za) + u * (ze - zd) : za + u * (zb - za) + v * (ze - zb);
          dev = std::max(dev, std::abs(double(h.at(i, j)) - z));
        }
      g.max_deviation[q] = dev;
    }
  g.mesh_vertices = g.vertices;
  const int columns = g.quads_x + 1;
  for (int r = 0; r < g.quads_y; ++r)
    for (int c = 0; c < g.quads_x; ++c) {
      const std::uint32_t a = r * columns + c, b = a + 1, d = a + columns, e = d + 1;
      g.cell_first.push_back(int(g.triangles.size()));
      g.triangles.insert(g.triangles.end(), {a, d, e, a, e, b});  // as build_grid_mesh
    }
  g.cell_first.push_back(int(g.triangles.size()));
  g.serial = next_grid_serial();
  return g;
}

std::uint64_t next_grid_serial() {
  static std::atomic<std::uint64_t> next{1};
  return next++;
}

glm::dvec3 coarse_reprojection(const CoarseGrid& g, int q, glm::dvec3 eye, glm::dvec3 point) {
  const glm::dvec3 to = point - eye;
  const double t_point = glm::length(to);
  if (t_point <= 0) return point;
  const glm::dvec3 d = to / t_point;
  double best_t = std::numeric_limits<double>::quiet_NaN();
  auto cell = [&](int n) {
    for (int t = g.cell_first[n]; t < g.cell_first[n + 1]; t += 3) {
      const double hit =
          ray_triangle(eye, d, g.mesh_vertices[g.triangles[t]], g.mesh_vertices[g.triangles[t + 1]],
                       g.mesh_vertices[g.triangles[t + 2]]);
      if (hit > 0 && (std::isnan(best_t) || std::abs(hit - t_point) < std::abs(best_t - t_point)))
        best_t = hit;
    }
  };
  if (g.adaptive) {
    for (int i = g.near_first[q]; i < g.near_first[q + 1]; ++i) cell(g.near_cells[i]);
  } else {
    const int col = q % g.quads_x, row = q / g.quads_x;
    for (int r = std::max(row - 1, 0); r <= std::min(row + 1, g.quads_y - 1); ++r)
      for (int c = std::max(col - 1, 0); c <= std::min(col + 1, g.quads_x - 1); ++c)
        cell(r * g.quads_x + c);
  }
  return std::isnan(best_t) ? point : eye + best_t * d;
}

double drape_displacement_px(const CoarseGrid& g, int q, const Camera& view, int height_px) {
  const glm::dvec3 d = g.centre[q] - view.position;
  const double dist2 = glm::dot(d, d);
  if (dist2 <= 0) return 0;
  // Angle moved = dz sin(ray to vertical) / dist, sin = horizontal / dist.
  return g.max_deviation[q] * glm::length(glm::dvec2(d)) / dist2 / view.pixel_angle(height_px);
}

bool drape_is_sharp(const CoarseGrid& g, int q, const Camera& view, int height_px,
                    double sharp_px) {
  return drape_displacement_px(g, q, view, height_px) < sharp_px;
}

namespace {
/// The angle of one pixel at the image centre, radians, exactly (tan-based).
double centre_pixel(const Camera& c, int height_px) {
  return 2.0 * std::tan(0.5 * glm::radians(c.fov_y_deg)) / height_px;
}
}  // namespace

KeyframeSamples make_keyframe_samples(const CoarseGrid& g, const Camera& key, int width, int height,
                                      std::span<const std::uint8_t> visible, int view_width,
                                      int view_height, double view_fov_y_deg) {
  assert(visible.size() == static_cast<std::size_t>(g.quad_count()));
  KeyframeSamples k;
  k.key = key;
  k.width = width;
  k.height = height;
  k.view_width = view_width > 0 ? view_width : width;
  k.view_height = view_height > 0 ? view_height : height;
  Camera view = key;
  if (view_fov_y_deg > 0) view.fov_y_deg = view_fov_y_deg;
  k.supersample = centre_pixel(view, k.view_height) / centre_pixel(key, height);
  k.c_prime.resize(visible.size());
  k.visible.assign(visible.begin(), visible.end());
  const glm::dvec3 fwd = key.forward();
  double best = -2.0;
  k.beta_reference = key.position + fwd * (0.5 * (key.near_m + key.far_m));
  for (std::size_t q = 0; q < visible.size(); ++q) {
    if (!g.has_centre[q]) {
      k.visible[q] = 0;
      k.c_prime[q] = g.centre[q];
      continue;
    }
    k.c_prime[q] = coarse_reprojection(g, int(q), key.position, g.centre[q]);
    if (!k.visible[q]) continue;
    const double along = glm::dot(glm::normalize(g.centre[q] - key.position), fwd);
    if (along > best) {
      best = along;
      k.beta_reference = g.centre[q];
    }
  }
  return k;
}

namespace {

// max(s1, 1/s2) for the singular values s1 >= s2 of d(view pixel)/d(key
// pixel) at C on the plane through C with normal n, by finite differences
// (steps of 1e-3 of C's distance from the key eye along two tangents).
// A plane seen edge-on in either view counts as a large stretch (64).
double anisotropic_stretch(const glm::dmat4& key_vp, const glm::dmat4& view_vp, int w, int h,
                           int vw, int vh, double supersample, glm::dvec3 C, glm::dvec3 n,
                           double key_distance) {
  constexpr double kEdgeOn = 64.0;
  const glm::dvec3 a = std::abs(n.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
  const double eps = 1e-3 * std::max(key_distance, 1e-6);
  const glm::dvec3 t1 = glm::normalize(glm::cross(n, a)) * eps,
                   t2 = glm::normalize(glm::cross(n, t1)) * eps;
  glm::dvec2 k0, k1, k2, v0, v1, v2;
  if (!project(key_vp, w, h, C, k0) || !project(key_vp, w, h, C + t1, k1) ||
      !project(key_vp, w, h, C + t2, k2) || !project(view_vp, vw, vh, C, v0) ||
      !project(view_vp, vw, vh, C + t1, v1) || !project(view_vp, vw, vh, C + t2, v2))
    return kEdgeOn;
  const glm::dmat2 K(k1 - k0, k2 - k0), V(v1 - v0, v2 - v0);
  const double det = glm::determinant(K);
  if (std::abs(det) < 1e-12 * std::max(glm::dot(K[0], K[0]) + glm::dot(K[1], K[1]), 1e-300))
    return kEdgeOn;
  const glm::dmat2 J = V * glm::inverse(K);
  // Singular values of a 2 x 2 matrix from its Frobenius norm and determinant.
  const double f = glm::dot(J[0], J[0]) + glm::dot(J[1], J[1]), d = std::abs(glm::determinant(J));
  const double root = std::sqrt(std::max(f * f / 4 - d * d, 0.0));
  const double s1 = std::sqrt(f / 2 + root), s2 = std::sqrt(std::max(f / 2 - root, 0.0));
  if (s2 <= 1.0 / kEdgeOn) return kEdgeOn;
  return std::min(std::max({s1, 1.0 / (s2 * supersample), 1.0}), kEdgeOn);
}

}  // namespace

SpriteError sprite_error(const CoarseGrid& g, const KeyframeSamples& k, const Camera& view) {
  SpriteError e;
  // Eq. (1) approximated as in the paper: one angle beta for every vertex,
  // the angle between the two eyes seen from the sample nearest the key's
  // view axis. In triangle (C, C', new eye) with |CC'| = b along the key ray,
  // the displacement subtends theta = atan2(b sin(beta), d +- b cos(beta)),
  // d = |new eye - C|, + when C' lies beyond C (C above the coarse surface).
  const glm::dvec3 P = k.beta_reference;
  const glm::dvec3 u1 = k.key.position - P, u2 = view.position - P;
  const double l1 = glm::length(u1), l2 = glm::length(u2);
  const double cos_beta =
      (l1 > 0 && l2 > 0) ? std::clamp(glm::dot(u1, u2) / (l1 * l2), -1.0, 1.0) : 1.0;
  const double sin_beta = std::sqrt(std::max(0.0, 1.0 - cos_beta * cos_beta));
  const int vw = k.view_width > 0 ? k.view_width : k.width;
  const int vh = k.view_height > 0 ? k.view_height : k.height;
  const double pixel = view.pixel_angle(vh);
  // View pixels per keyframe pixel of equal solid angle at the image centres,
  // squared: the footprints below are per steradian.
  const double density = std::pow(centre_pixel(k.key, k.height) / centre_pixel(view, vh), 2.0);
  const double log_supersample = std::log(std::max(k.supersample, 1e-9));
  const glm::dmat4 vp = view.view_projection();
  const glm::dvec3 forward = view.forward();
  double sum_paper = 0, sum_exact = 0, sum_log_scale = 0, sum_log_aniso = 0, sum_contrast = 0,
         sum_weight = 0, sum_drape = 0, sum_view_weight = 0;
  const bool contrast = !k.gradient.empty();
  const glm::dmat4 key_vp = k.key.view_projection();
  const glm::dvec3 key_forward = k.key.forward();
  // Pixels covering a small patch at C: dA |cos(incidence)| / (d^2 cos^3(off-axis angle)), up to
  // each view's pixels per steradian (`density` carries their ratio).
  auto footprint = [](glm::dvec3 eye, glm::dvec3 axis, glm::dvec3 c, glm::dvec3 normal) {
    const glm::dvec3 to = eye - c;
    const double d = glm::length(to);
    const double incidence = std::max(std::abs(glm::dot(normal, to / d)), 1e-3);
    const double off_axis = std::max(glm::dot(-to / d, axis), 1e-3);
    return incidence / (d * d * off_axis * off_axis * off_axis);
  };
  for (std::size_t q = 0; q < k.visible.size(); ++q) {
    if (!g.has_centre[q]) continue;
    const glm::dvec3& C = g.centre[q];
    glm::dvec2 pc;
    if (!project(vp, vw, vh, C, pc) || !inside_image(pc, vw, vh)) continue;
    if (glm::dot(C - view.position, forward) < view.near_m) continue;
    ++e.in_view;
    const double w = g.weight.empty() ? 1.0 : g.weight[q];
    const double drape = drape_displacement_px(g, int(q), view, vh);
    sum_drape += w * drape * drape;
    sum_view_weight += w;
    if (!k.visible[q]) continue;
    ++e.samples;
    sum_weight += w;
    const double b = g.edge_offset[q];
    const double d = glm::length(view.position - C);
    const double theta = std::atan2(std::abs(b) * sin_beta, d + b * cos_beta) / pixel;
    sum_paper += w * theta * theta;
    const double area_ratio = footprint(view.position, forward, C, g.normal[q]) /
                              footprint(k.key.position, key_forward, C, g.normal[q]) * density;
    // Stretch (log s > 0) always counts; shrinking only past the keyframe's
    // supersampling (a denser keyframe is meant to be shrunk that much).
    const double log_s = 0.5 * std::log(area_ratio);
    sum_log_scale += w * std::max({log_s, -log_s - log_supersample, 0.0});
    sum_log_aniso +=
        w * std::log(anisotropic_stretch(key_vp, vp, k.width, k.height, vw, vh, k.supersample, C,
                                         g.normal[q], glm::length(k.key.position - C)));
    glm::dvec2 pp;
    if (project(vp, vw, vh, k.c_prime[q], pp)) {
      const glm::dvec2 dp = pp - pc;
      sum_exact += w * glm::dot(dp, dp);
      if (contrast) {
        const double level = std::min(double(k.gradient[q]) * glm::length(dp),
                                      std::sqrt(2.0) * double(k.deviation[q]));
        sum_contrast += w * level * level;
      }
    }
  }
  if (e.in_view > 0) e.drape_px = std::sqrt(sum_drape / sum_view_weight);
  if (e.samples > 0) {
    e.paper_px = std::sqrt(sum_paper / sum_weight);
    e.exact_px = std::sqrt(sum_exact / sum_weight);
    e.contrast_levels = std::sqrt(sum_contrast / sum_weight);
    e.resample_scale = std::exp(sum_log_scale / sum_weight);
    e.resample_aniso = std::exp(sum_log_aniso / sum_weight);
  }
  return e;
}

}  // namespace terrasprite
