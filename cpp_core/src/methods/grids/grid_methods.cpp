#include "tessella/grid_methods.h"

#include <algorithm>
#include <cmath>

#include "geometry/trim_deflection.h"
#include "geometry/uv_trim_classifier.h"
#include "mesh/grid_clipping.h"
#include "mesh/seam_sides.h"
#include "tessella/errors.h"
#include "tessella/surface_face.h"

namespace tessella {

namespace {

constexpr int kAlong = 256;  // samples along a parameter direction
constexpr int kAcross = 33;  // iso-curves averaged across it

// Arc length per unit parameter along u (along_u) or v, averaged over iso-curves
// across the face; only points inside the trimmed face count, so the cut-away
// part of the underlying surface does not steer the spacing. Returns the
// cumulative arc length at kAlong+1 evenly spaced parameters.
std::vector<double> cumulative_arc_length(const SurfaceFace& face, bool along_u) {
  const UvBounds b = face.bounds();
  const double a0 = along_u ? b.u_min : b.v_min, a1 = along_u ? b.u_max : b.v_max;
  const double c0 = along_u ? b.v_min : b.u_min, c1 = along_u ? b.v_max : b.u_max;
  // Inside test by the crossings of each iso-line with the trim classifier at
  // the steering deflection: 20x faster than OCCT's classifier per point, and
  // exact enough for averaging.
  const UvTrimClassifier trim(face.trim_loops(steering_trim_deflection(face)));
  std::vector<double> speed(kAlong + 1, 0.0);
  for (int i = 0; i <= kAlong; ++i) {
    const double a = a0 + (a1 - a0) * i / kAlong;
    const std::vector<double> crossings = trim.crossings(along_u ? 1 : 0, a);
    double inside_sum = 0, all_sum = 0;
    int inside_n = 0;
    std::size_t passed = 0;
    for (int j = 0; j <= kAcross; ++j) {
      // Sample cell centres across so a trim along the border does not decide.
      const double c = c0 + (c1 - c0) * (j + 0.5) / (kAcross + 1);
      const double u = along_u ? a : c, v = along_u ? c : a;
      const SurfacePoint d = face.derivatives(u, v);
      const double s = (along_u ? d.du : d.dv).norm();
      all_sum += s;
      while (passed < crossings.size() && crossings[passed] < c) ++passed;
      if (passed % 2 == 1) inside_sum += s, ++inside_n;
    }
    speed[i] = inside_n > 0 ? inside_sum / inside_n : all_sum / (kAcross + 1);
  }
  std::vector<double> cumulative(kAlong + 1, 0.0);
  const double h = (a1 - a0) / kAlong;
  for (int i = 1; i <= kAlong; ++i)
    cumulative[i] = cumulative[i - 1] + 0.5 * h * (speed[i - 1] + speed[i]);
  return cumulative;
}

int count_for_size(double length, double size, const char* direction, int fewest) {
  const double n = std::max(double(fewest), std::round(length / size));
  if (n > 1e7) {
    throw LimitExceeded(std::string("size is too small: ") + direction + " alone would need " +
                        std::to_string(static_cast<long long>(n)) + " panels");
  }
  return static_cast<int>(n);
}

std::vector<double> uniform_lines(double lo, double hi, int count) {
  std::vector<double> lines(count + 1);
  for (int i = 0; i <= count; ++i) lines[i] = lo + (hi - lo) * i / count;
  lines.back() = hi;
  return lines;
}

// Lines at equal steps of the cumulative arc length (piecewise-linear inverse).
std::vector<double> arc_length_lines(double lo, double hi, const std::vector<double>& cumulative,
                                     int count) {
  std::vector<double> lines(count + 1);
  lines[0] = lo;
  lines[count] = hi;
  const double total = cumulative.back();
  std::size_t k = 1;
  for (int i = 1; i < count; ++i) {
    const double target = total * i / count;
    while (k < cumulative.size() - 1 && cumulative[k] < target) ++k;
    const double c0 = cumulative[k - 1], c1 = cumulative[k];
    const double t = c1 > c0 ? (target - c0) / (c1 - c0) : 0.5;
    lines[i] = lo + (hi - lo) * (double(k - 1) + t) / double(cumulative.size() - 1);
  }
  // Where the surface has no length (a pole edge) two lines can coincide: keep one.
  const double eps = 1e-9 * (hi - lo);
  std::vector<double> kept{lines.front()};
  for (int i = 1; i < count; ++i)
    if (lines[i] - kept.back() > eps && hi - lines[i] > eps) kept.push_back(lines[i]);
  kept.push_back(hi);
  return kept;
}

void check_clip_params(const GridClipParams& p, int u_count, int v_count) {
  require_in_range("max_panels", p.max_panels, 1, 1e8);
  require_in_range("sliver_fraction", p.sliver_fraction, 0.0, 1.0);
  require_in_range("trim_deflection", p.trim_deflection, 0.0, 1e9);
  const double cells = double(u_count) * double(v_count);
  if (cells > p.max_panels) {
    throw LimitExceeded("the grid would have " + std::to_string(static_cast<long long>(cells)) +
                        " panels (" + std::to_string(u_count) + " x " + std::to_string(v_count) +
                        "), more than max_panels = " + std::to_string(p.max_panels) +
                        ": choose a larger size or raise max_panels");
  }
}

void check_size(double size) {
  // 1 micrometre to 1000 km: anything outside is a unit mistake, not a design.
  require_in_range("size (mm)", size, 1e-3, 1e9);
}

}  // namespace

GridLines iso_grid_lines(const SurfaceFace& face, const IsoGridParams& params) {
  const bool by_size = params.size != 0.0;
  const bool by_count = params.u_count != 0 || params.v_count != 0;
  if (by_size && by_count) {
    throw InvalidParameter("give either size or u_count and v_count, not both");
  }
  if (!by_size && !by_count) {
    throw InvalidParameter("give size (mm) > 0, or u_count and v_count >= 1");
  }
  int nu, nv;
  if (by_size) {
    check_size(params.size);
    nu = count_for_size(cumulative_arc_length(face, true).back(), params.size, "u",
                        fewest_cells_along(face, true));
    nv = count_for_size(cumulative_arc_length(face, false).back(), params.size, "v",
                        fewest_cells_along(face, false));
  } else {
    require_in_range("u_count", params.u_count, 1, 1e6);
    require_in_range("v_count", params.v_count, 1, 1e6);
    for (const bool along_u : {true, false}) {
      const int fewest = fewest_cells_along(face, along_u);
      const int count = along_u ? params.u_count : params.v_count;
      if (count < fewest)
        throw InvalidParameter(std::string(along_u ? "u_count" : "v_count") + " must be at least " +
                               std::to_string(fewest) + " on this face (" +
                               (fewest == 3 ? "closed in that direction" : "a pole at both ends") +
                               ": fewer cells give panels without area or panels that coincide)");
    }
    nu = params.u_count;
    nv = params.v_count;
  }
  check_clip_params(params.clip, nu, nv);
  const UvBounds b = face.bounds();
  return {uniform_lines(b.u_min, b.u_max, nu), uniform_lines(b.v_min, b.v_max, nv)};
}

PanelMesh iso_grid(const SurfaceFace& face, const IsoGridParams& params) {
  return grid_on_lines(face, iso_grid_lines(face, params), params.clip);
}

GridLines equal_size_grid_lines(const SurfaceFace& face, const EqualSizeGridParams& params) {
  if (params.size == 0.0) throw InvalidParameter("size (mm) is required for equal_size_grid");
  check_size(params.size);
  const std::vector<double> cu = cumulative_arc_length(face, true);
  const std::vector<double> cv = cumulative_arc_length(face, false);
  const int nu = count_for_size(cu.back(), params.size, "u", fewest_cells_along(face, true));
  const int nv = count_for_size(cv.back(), params.size, "v", fewest_cells_along(face, false));
  check_clip_params(params.clip, nu, nv);
  const UvBounds b = face.bounds();
  return {arc_length_lines(b.u_min, b.u_max, cu, nu), arc_length_lines(b.v_min, b.v_max, cv, nv)};
}

PanelMesh equal_size_grid(const SurfaceFace& face, const EqualSizeGridParams& params) {
  return grid_on_lines(face, equal_size_grid_lines(face, params), params.clip);
}

PanelMesh grid_on_lines(const SurfaceFace& face, const GridLines& lines,
                        const GridClipParams& clip) {
  if (lines.u.size() < 2 || lines.v.size() < 2)
    throw InvalidParameter("grid_on_lines: at least two lines in u and in v");
  check_clip_params(clip, static_cast<int>(lines.u.size()) - 1,
                    static_cast<int>(lines.v.size()) - 1);
  return clip_grid(face, lines.u, lines.v, clip);
}

}  // namespace tessella
