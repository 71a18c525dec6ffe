// SPDX-License-Identifier: MIT
// The LOD-sprite error metric and keyframe visibility (Chen, Swan, Kuo,
// Kaufman, IEEE Visualization 1999, section 3.2 Eq. 1-2 and section 3.3),
// on the CPU and without GL, so it can be tested and simulated cheaply.
#pragma once
#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "terrasprite/camera/camera.h"
#include "terrasprite/terrain/heightfield.h"

namespace terrasprite {

/// The coarse grid of `quads` quads per side (terrain/pyramid.h: quad_indices)
/// and, per coarse quad, its centre vertex C: the full-resolution sample at the
/// middle of the quad, which the coarse mesh does not contain. Keyframe
/// independent; built once per terrain and coarse level.
///
///   a ---- b      coarse quad, rows run south; triangles (a, d, e) and
///   |  \   |      (a, e, b): the diagonal a-e runs NW to SE, and C sits on
///   |   C  |      (or, for an odd sample step, next to) it
///   |    \ |
///   d ---- e
struct CoarseGrid {
  int quads_x = 0, quads_y = 0;
  std::vector<int> xs, ys;  ///< coarse sample indices per axis (quads + 1 each)
  std::vector<glm::dvec3>
      vertices;  ///< (quads_y + 1) x (quads_x + 1) coarse vertices, row-major, metres
  std::vector<glm::dvec3> centre;  ///< C per quad (row-major, quads_y x quads_x), metres
  std::vector<std::uint8_t>
      has_centre;  ///< 0 where the quad is one sample wide (no vertex strictly inside)
  /// b of the paper's approximation: distance (m) from C to the quad's coarse
  /// diagonal edge a-e (adaptive: the drawn edge C lies on), signed + where C
  /// lies above the edge, - below (signed_edge_offset).
  std::vector<double> edge_offset;
  /// Unit surface normal of the full-resolution grid at C (central differences).
  std::vector<glm::dvec3> normal;
  /// Per quad: the largest vertical distance (m) between a full-resolution
  /// sample inside it and the coarse surface (its two triangles).
  std::vector<double> max_deviation;

  /// The mesh as drawn, uniform and adaptive grids alike. A "quad" is a cell:
  /// a uniform grid's quad, or a leaf of an adaptive mesh (adaptive_mesh.h),
  /// whose per-cell arrays above then hold one entry per leaf (quads_y = 1,
  /// quads_x = cells; `vertices`, xs and ys are empty, vertex() unusable).
  /// Uniform: mesh_vertices == vertices and the same triangles as
  /// build_grid_mesh (6 indices per quad).
  std::vector<glm::dvec3> mesh_vertices;      ///< metres
  std::vector<std::uint32_t> triangles;       ///< into mesh_vertices, grouped by cell
  std::vector<int> cell_first;                ///< cell q: triangles[cell_first[q], cell_first[q+1])
  std::vector<int> near_first, near_cells;    ///< adaptive: cells touching cell q (and q)
  std::vector<std::array<int, 4>> cell_rect;  ///< adaptive: sample rectangle x0, y0, x1, y1
  /// Adaptive: per cell, the weight of its sample in the metric's means: its
  /// area in samples, so a mean over cells is, as on the uniform grid, a mean
  /// over the terrain's area (not over cells, which are small near the
  /// keyframe's camera). Empty: all 1 (the uniform grid, the paper's mean).
  std::vector<double> weight;
  bool adaptive = false;
  /// Changes with every grid made (to tell grids apart without comparing them).
  std::uint64_t serial = 0;

  int quad_count() const { return quads_x * quads_y; }
  long long triangle_count() const { return static_cast<long long>(triangles.size() / 3); }
  const glm::dvec3& vertex(int col, int row) const {
    return vertices[static_cast<std::size_t>(row) * (quads_x + 1) + col];
  }
};

/// Builds the grid; quads is clamped like quad_indices. h has >= 2 x 2 samples.
CoarseGrid make_coarse_grid(const Heightfield& h, int quads);

/// b of the paper's approximation for sample C over the drawn edge a-e: the
/// distance from C to the segment, + where C lies above the edge (compared
/// at C's horizontal position projected on it), - below.
double signed_edge_offset(glm::dvec3 C, glm::dvec3 a, glm::dvec3 e);
/// Unit surface normal of the full-resolution grid at sample (i, j) (central
/// differences, one-sided at the borders; rows run south).
glm::dvec3 grid_normal(const Heightfield& h, int i, int j);

/// A fresh CoarseGrid::serial.
std::uint64_t next_grid_serial();

/// Where the ray from `eye` through `point` meets the coarse surface of cell
/// `q` or the cells around it (a uniform grid's 8 neighbours, an adaptive
/// mesh's touching leaves): the hit nearest to `point` along the ray.
/// Returns `point` itself when the ray misses all of them (grazing rays).
glm::dvec3 coarse_reprojection(const CoarseGrid& grid, int q, glm::dvec3 eye, glm::dvec3 point);

/// Ours: how far plain LOD's drape of cell `q` is off in `view` (a
/// `height_px` pixels high image), in pixels at its centre C: its largest
/// vertical deviation from the full-resolution surface
/// (CoarseGrid::max_deviation, metres) times sin(angle of the ray from the
/// eye to C to the vertical), over the distance, per pixel angle. 0 seen
/// from straight above, the whole deviation edge-on.
double drape_displacement_px(const CoarseGrid& grid, int q, const Camera& view, int height_px);

/// Ours: whether cell `q`'s drape texture is already sharp in `view` (a
/// `height_px` pixels high image): its largest vertical deviation from the
/// full-resolution surface (CoarseGrid::max_deviation, metres) moves the
/// image by under `sharp_px` pixels at its centre C. The image moves by the
/// offset's component across the ray from the eye to C, dz sin(angle of the
/// ray to the vertical): seen from straight above a vertical error does not
/// move the image at all, seen edge-on it moves by all of it.
bool drape_is_sharp(const CoarseGrid& grid, int q, const Camera& view, int height_px,
                    double sharp_px);

/// Depth buffer of a keyframe: linear depth in metres along the key camera's
/// view axis, width*height, row 0 on top (RenderTarget::read_depth), +inf = sky.
struct DepthView {
  std::span<const float> depth;
  int width = 0, height = 0;
};

/// True when world point `p` is inside `key`'s view (in front, within the
/// image) and not hidden in `depth`: its view-axis distance is at most the
/// farthest depth in the 3x3 pixels around its projection, plus a relative
/// tolerance `rel_tolerance` (rasterised depth differs from a vertex's within a pixel).
bool visible_in_keyframe(const Camera& key, const DepthView& depth, glm::dvec3 p,
                         double rel_tolerance = 0.003);

/// Pixel position (x right, y down, pixel centres at +0.5) of `p` in `camera`'s
/// width x height image; false when p is behind the eye.
bool project_to_pixel(const Camera& camera, int width, int height, glm::dvec3 p, glm::dvec2& pixel);

/// What the metric keeps of a keyframe: its camera and image size, and per
/// coarse quad C' (the reprojection of C through the key eye onto the coarse
/// surface) and whether C was visible in the keyframe.
struct KeyframeSamples {
  Camera key;
  int width = 0, height = 0;  ///< the keyframe image, pixels
  /// The image the sprite frames are drawn at, pixels. It may be smaller than
  /// the keyframe's: a keyframe may see past the view's edges (a wider field
  /// of view, same aspect) and sample it more densely (SpriteOptions::key_margin,
  /// key_supersample). Then `supersample` = keyframe pixels per view pixel at
  /// equal camera (linear, >= 1 expected).
  int view_width = 0, view_height = 0;
  double supersample = 1.0;
  std::vector<glm::dvec3> c_prime;    ///< per quad, metres
  std::vector<std::uint8_t> visible;  ///< per quad: C unoccluded and inside the key view
  glm::dvec3 beta_reference{
      0.0};  ///< the visible C nearest the key's view axis (where beta is measured)
  /// Per quad, for ErrorMetric::kContrast only (empty otherwise): the
  /// keyframe's RMS luminance gradient (grey levels per pixel) and luminance
  /// standard deviation (grey levels) over the quad's footprint in it.
  std::vector<float> gradient, deviation;
};

/// Builds the samples. `visible` holds one flag per quad (C visible in the
/// keyframe); its size is grid.quad_count(). `width` x `height` is the
/// keyframe image; `view_width` x `view_height` the sprite frames' (0: the
/// keyframe's), drawn with `view_fov_y_deg` (0: the keyframe's) at the same aspect.
KeyframeSamples make_keyframe_samples(const CoarseGrid& grid, const Camera& key, int width,
                                      int height, std::span<const std::uint8_t> visible,
                                      int view_width = 0, int view_height = 0,
                                      double view_fov_y_deg = 0);

enum class ErrorMetric {
  kPaper,  ///< the paper's approximation: common angle beta, b from C's distance to the coarse edge
  kExact,  ///< exact reprojection: pixel distance between C and C' projected into the new view
  /// Predicted image error: per sample, the exact displacement d (pixels)
  /// times the keyframe's luminance gradient there, capped at sqrt(2) times
  /// its luminance deviation (a shift past the texture's features errs by at
  /// most the difference of unrelated samples); the RMS in grey levels
  /// (0-255). Needs KeyframeSamples::gradient and ::deviation; without them it is 0.
  kContrast,
};

/// A new view's error against a keyframe. Both variants are the root of the
/// mean squared per-sample error, in pixels (adaptive grids: each sample weighted
/// by its cell's area, CoarseGrid::weight), so the paper's test
/// "mean squared error > threshold^2" reads error > threshold.
struct SpriteError {
  double paper_px =
      0;  ///< Eq. 1-2: angle(C, C') seen from the new eye / pixel angle (fov / height)
  double exact_px = 0;  ///< |project(C) - project(C')| in pixels
  int samples = 0;      ///< quads whose C is in the new view and was visible in the keyframe
  int in_view = 0;      ///< quads whose C is in the new view
  /// Fraction of in-view centres that were not visible in the keyframe (they fall back to the drape
  /// texture).
  double fallback_fraction() const {
    return in_view > 0 ? double(in_view - samples) / in_view : 0.0;
  }
  /// How much the keyframe's pixels are stretched or shrunk in the new view:
  /// per sample, the linear scale s (view pixels per keyframe pixel) between
  /// the pixel footprints of the surface at C in the two views (distance,
  /// foreshortening against C's normal, off-axis pixel size), folded to
  /// max(s, 1/(s k), 1) for a keyframe supersampled k times
  /// (KeyframeSamples::supersample; k = 1: max(s, 1/s)); the geometric mean
  /// over the samples. 1 = no worse than the keyframe's own density. A sprite resamples the
  /// keyframe bilinearly, so a large scale blurs (or aliases) even when the
  /// geometric error is small, e.g. on low-relief terrain.
  double resample_scale = 1.0;
  /// The same per direction: per sample, the singular values s1 >= s2 of
  /// the Jacobian from keyframe pixels to new-view pixels on the plane of
  /// C's coarse normal, folded to max(s1, 1/(s2 k), 1) (the worst-stretched or
  /// worst-shrunk axis); the geometric mean over the samples. At least
  /// resample_scale's figure for each sample; larger where the view turns or
  /// tilts so the keyframe is stretched one way and shrunk the other (equal
  /// area, yet blurred along one axis).
  double resample_aniso = 1.0;
  /// Ours: how far plain LOD of the same coarse mesh would be off in this
  /// view: the RMS over the in-view cells (visible in the keyframe or not;
  /// adaptive: weighted by area) of drape_displacement_px, pixels. Keyframe
  /// independent. Large where the coarse mesh is far from the terrain
  /// (relief, oblique views), near 0 on flat ground or seen from overhead.
  double drape_px = 0;
  /// ErrorMetric::kContrast: RMS predicted intensity error, grey levels (0-255).
  double contrast_levels = 0;
  /// The metric's figure: pixels for kPaper and kExact, grey levels for kContrast.
  double value(ErrorMetric m) const {
    return m == ErrorMetric::kPaper   ? paper_px
           : m == ErrorMetric::kExact ? exact_px
                                      : contrast_levels;
  }
};

/// Error of `view` (a KeyframeSamples::view_width x view_height image) against the keyframe.
/// No samples give zero error.
SpriteError sprite_error(const CoarseGrid& grid, const KeyframeSamples& key, const Camera& view);

}  // namespace terrasprite
