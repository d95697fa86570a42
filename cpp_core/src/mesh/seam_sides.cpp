#include "mesh/seam_sides.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "tessella/surface_face.h"

namespace tessella {

namespace {

bool spans_period(bool periodic, double lo, double hi, double period) {
  return periodic && period > 0 && hi - lo >= period * (1 - 1e-9);
}

// Seam of one axis (0: u = u0 or u0 + period; 1: the same in v).
void join_along(PanelMesh& m, int axis, double lo, double period) {
  const int along = 1 - axis;
  const double eps = 1e-9 * period;
  auto side_of = [&](double c) {  // 0 / 1: which copy of the seam; -1: off it
    if (std::abs(c - lo) <= eps) return 0;
    if (std::abs(c - (lo + period)) <= eps) return 1;
    return -1;
  };
  // The seam's vertices by their parameter along it (from the corners that
  // lie on it; a vertex once).
  std::vector<std::pair<double, int>> seam;
  for (std::size_t p = 0; p < m.panels.size(); ++p)
    for (std::size_t i = 0; i < m.panels[p].size(); ++i)
      if (side_of(m.corner_uv[p][i][axis]) >= 0)
        seam.push_back({m.corner_uv[p][i][along], m.panels[p][i]});
  std::sort(seam.begin(), seam.end(),
            [](const auto& a, const auto& b) { return a.second < b.second; });
  seam.erase(std::unique(seam.begin(), seam.end(),
                         [](const auto& a, const auto& b) { return a.second == b.second; }),
             seam.end());
  std::sort(seam.begin(), seam.end());
  if (seam.size() < 3) return;
  for (std::size_t p = 0; p < m.panels.size(); ++p) {
    const std::vector<int>& panel = m.panels[p];
    const std::vector<Vec2>& uv = m.corner_uv[p];
    const std::size_t n = panel.size();
    std::vector<int> out;
    std::vector<Vec2> out_uv;
    for (std::size_t i = 0; i < n; ++i) {
      out.push_back(panel[i]);
      out_uv.push_back(uv[i]);
      // Exactly on its copy of the seam: a straight (u,v) line along the seam
      // then passes through the seam vertices, not a rounding beside them
      // (boundary pieces may not cut a panel along it).
      const int on = side_of(uv[i][axis]);
      if (on >= 0) out_uv.back()[axis] = on == 0 ? lo : lo + period;
      const std::size_t j = (i + 1) % n;
      if (on < 0 || side_of(uv[j][axis]) != on) continue;  // not a side along the seam
      const double a = uv[i][along], b = uv[j][along];
      const auto first = std::upper_bound(seam.begin(), seam.end(), std::min(a, b),
                                          [](double t, const auto& x) { return t < x.first; });
      const auto last = std::lower_bound(seam.begin(), seam.end(), std::max(a, b),
                                         [](const auto& x, double t) { return x.first < t; });
      std::vector<std::pair<double, int>> between(first, std::max(first, last));
      if (a > b) std::reverse(between.begin(), between.end());
      for (const auto& [t, v] : between) {
        if (v == panel[i] || v == panel[j]) continue;
        Vec2 q = out_uv.back();
        q[along] = t;
        out.push_back(v);
        out_uv.push_back(q);
      }
    }
    m.panels[p] = std::move(out);
    m.corner_uv[p] = std::move(out_uv);
  }
}

}  // namespace

bool closed_round_a_seam(const SurfaceFace& face) {
  const UvBounds b = face.bounds();
  return spans_period(face.u_periodic(), b.u_min, b.u_max, face.u_period()) ||
         spans_period(face.v_periodic(), b.v_min, b.v_max, face.v_period());
}

bool closed_along(const SurfaceFace& face, int axis) {
  const UvBounds b = face.bounds();
  return axis == 0 ? spans_period(face.u_periodic(), b.u_min, b.u_max, face.u_period())
                   : spans_period(face.v_periodic(), b.v_min, b.v_max, face.v_period());
}

bool runs_along_seam(const SurfaceFace& face, const Vec2& a, const Vec2& b) {
  const UvBounds bounds = face.bounds();
  auto along = [](bool spans, double period, double lo, double hi, double x, double y) {
    if (!spans) return false;
    const double eps = 1e-9 * period;
    return (std::abs(x - lo) <= eps && std::abs(y - lo) <= eps) ||
           (std::abs(x - hi) <= eps && std::abs(y - hi) <= eps);
  };
  return along(spans_period(face.u_periodic(), bounds.u_min, bounds.u_max, face.u_period()),
               face.u_period(), bounds.u_min, bounds.u_max, a.x(), b.x()) ||
         along(spans_period(face.v_periodic(), bounds.v_min, bounds.v_max, face.v_period()),
               face.v_period(), bounds.v_min, bounds.v_max, a.y(), b.y());
}

std::vector<double> rim_lengths(const SurfaceFace& face, const std::vector<TrimLoop>& loops) {
  std::vector<double> out;
  const double periods[2] = {face.u_period(), face.v_period()};
  const double tiny = 1e-9 * face.model_size();
  for (int axis = 0; axis < 2; ++axis) {
    if (!closed_along(face, axis)) continue;
    for (const TrimLoop& loop : loops) {
      const std::size_t n = loop.uv.size();
      if (n < 2) continue;
      auto seam = [&](std::size_t k) {
        return runs_along_seam(face, loop.uv[k % n], loop.uv[(k + 1) % n]);
      };
      // Start right after a seam segment, so no run wraps past the end.
      std::size_t start = 0;
      for (std::size_t k = 0; k < n; ++k)
        if (seam(k)) {
          start = k + 1;
          break;
        }
      double length = 0, lo = loop.uv[start % n][axis], hi = lo;
      for (std::size_t j = 0; j < n; ++j) {
        const std::size_t k = start + j;
        const bool ends = seam(k) || j + 1 == n;
        if (!seam(k)) {
          length += (loop.xyz[(k + 1) % n] - loop.xyz[k % n]).norm();
          const double x = loop.uv[(k + 1) % n][axis];
          lo = std::min(lo, x), hi = std::max(hi, x);
        }
        if (!ends) continue;
        if (hi - lo >= (1 - 1e-6) * periods[axis] && length > tiny) out.push_back(length);
        length = 0;
        lo = hi = loop.uv[(k + 1) % n][axis];
      }
    }
  }
  std::sort(out.rbegin(), out.rend());
  return out;
}

double panel_turn(const SurfaceFace& face, const std::vector<Vec2>& corner_uv) {
  double widest = 0;
  const double periods[2] = {face.u_period(), face.v_period()};
  for (int axis = 0; axis < 2; ++axis) {
    if (!closed_along(face, axis)) continue;
    const double period = periods[axis];
    bool first = true;
    double x = 0, lo = 0, hi = 0, last = 0;
    for (const Vec2& c : corner_uv) {
      const SurfacePoint d = face.derivatives(c.x(), c.y());
      const double along = (axis == 0 ? d.du : d.dv).norm();
      const double across = (axis == 0 ? d.dv : d.du).norm();
      if (!(along > 1e-9 * across)) continue;  // a pole: no place round the axis
      if (first) {
        first = false;
        x = lo = hi = last = c[axis];
        continue;
      }
      x += (c[axis] - last) + seam_shift(last, c[axis], period);
      last = c[axis];
      lo = std::min(lo, x), hi = std::max(hi, x);
    }
    widest = std::max(widest, (hi - lo) / period);
  }
  return widest;
}

double widest_panel_round(const SurfaceFace& face, const PanelMesh& mesh) {
  double widest = 0;
  if (!closed_round_a_seam(face)) return widest;
  for (std::size_t p = 0; p < mesh.panels.size(); ++p)
    widest = std::max(widest, panel_turn(face, panel_corner_uv(mesh, p)));
  return widest;
}

int fewest_cells_along(const SurfaceFace& face, bool along_u) {
  const UvBounds b = face.bounds();
  const bool periodic = along_u ? face.u_periodic() : face.v_periodic();
  const double span = along_u ? b.u_max - b.u_min : b.v_max - b.v_min;
  if (periodic && span >= (along_u ? face.u_period() : face.v_period()) * (1 - 1e-9)) return 3;
  // Both ends of the direction poles: the iso-curves there have no length.
  auto pole = [&](double at) {
    double length = 0;
    const int n = 8;
    for (int i = 0; i <= n; ++i) {
      const double c =
          along_u ? b.v_min + (b.v_max - b.v_min) * i / n : b.u_min + (b.u_max - b.u_min) * i / n;
      const SurfacePoint d = along_u ? face.derivatives(at, c) : face.derivatives(c, at);
      length +=
          (along_u ? d.dv : d.du).norm() * (along_u ? b.v_max - b.v_min : b.u_max - b.u_min) / n;
    }
    return length <= 1e-9 * face.model_size();
  };
  const double lo = along_u ? b.u_min : b.v_min, hi = along_u ? b.u_max : b.v_max;
  return pole(lo) && pole(hi) ? 2 : 1;
}

namespace {

// A loose seam along `axis`: the hair by which the face's range exceeds
// (or falls short of) the period it spans, and how far apart its two copies
// are in space; {0, 0} where the copies are one within 1e-9 of the face's
// size (the seam weld's own tolerance), the hair is over 1e-6 of the
// period, or the face is not closed there. (FreeCAD's CAP_50SGV: one face
// 5.9e-7 of its period over it, its copies 4.6e-6 mm apart; another within
// 1e-9 of its period, its copies still 1.2e-8 mm apart on an 11 mm part.)
struct LooseSeam {
  double hair = 0, gap = 0;
};
LooseSeam loose_seam(const SurfaceFace& face, int axis) {
  const UvBounds b = face.bounds();
  const double lo = axis == 0 ? b.u_min : b.v_min, hi = axis == 0 ? b.u_max : b.v_max;
  const double period = axis == 0 ? face.u_period() : face.v_period();
  const bool periodic = axis == 0 ? face.u_periodic() : face.v_periodic();
  if (!spans_period(periodic, lo, hi, period)) return {};
  const double hair = hi - lo - period;
  if (hair == 0.0 || std::abs(hair) > 1e-6 * period) return {};
  const double a0 = axis == 0 ? b.v_min : b.u_min, a1 = axis == 0 ? b.v_max : b.u_max;
  double gap = 0;
  const int n = 16;
  for (int i = 0; i <= n; ++i) {
    const double t = a0 + (a1 - a0) * i / n;
    const Vec3 p0 = axis == 0 ? face.point(lo, t) : face.point(t, lo);
    const Vec3 p1 = axis == 0 ? face.point(hi, t) : face.point(t, hi);
    gap = std::max(gap, (p1 - p0).norm());
  }
  if (!(gap > 1e-9 * face.model_size())) return {};
  return {hair, gap};
}

void weld_loose_seams(const SurfaceFace& face, PanelMesh& mesh, const LooseSeam (&seams)[2]) {
  const UvBounds b = face.bounds();
  for (int axis = 0; axis < 2; ++axis) {
    const LooseSeam& seam = seams[axis];
    if (seam.gap == 0.0) continue;
    const double lo = axis == 0 ? b.u_min : b.v_min, hi = axis == 0 ? b.u_max : b.v_max;
    // One position by the face sets' and the tests' measure: the copies'
    // distance alone leaves the trim corners where an edge meets the seam
    // apart (their pcurves end within the vertex's tolerance, 4.9e-7 mm).
    const double tol = 1e-6 * face.model_size();
    // The vertices on either copy (a node a method traced onto the seam may
    // sit within the hair of it).
    const double near = std::abs(seam.hair) + 1e-9 * (hi - lo);
    std::vector<char> on_seam(mesh.vertex_count(), 0);
    for (std::size_t p = 0; p < mesh.panels.size(); ++p) {
      const std::vector<Vec2> uv = panel_corner_uv(mesh, p);
      for (std::size_t i = 0; i < uv.size(); ++i)
        if (std::abs(uv[i][axis] - lo) <= near || std::abs(uv[i][axis] - hi) <= near)
          on_seam[static_cast<std::size_t>(mesh.panels[p][i])] = 1;
    }
    weld_coincident_vertices(mesh, tol, on_seam);
  }
}

}  // namespace

void weld_loose_seam(const SurfaceFace& face, PanelMesh& mesh) {
  const LooseSeam seams[2] = {loose_seam(face, 0), loose_seam(face, 1)};
  weld_loose_seams(face, mesh, seams);
}

namespace {

// Whether the face's two sides along `axis` (u = u_min and u = u_max, or
// the same in v) are one curve in space while the surface is not periodic
// there: a B-spline band closed on itself (OCCT's Pump_TopCover), whose
// seam edge each method meets from both sides. A pole at an end of the
// seam (a B-spline cone with its apex) is no obstacle: the join along the
// seam is the periodic face's, which meets such poles on every cone. The
// seam itself must have a length: two sides collapsed into one point (a
// spindle's) are no seam.
bool closed_on_itself(const SurfaceFace& face, int axis) {
  if (axis == 0 ? face.u_periodic() : face.v_periodic()) return false;
  const UvBounds b = face.bounds();
  const double tiny = 1e-9 * face.model_size();
  const int n = 8;
  // A point of the face at `along` across the seam and `across` along it.
  auto at = [&](double along, double across) {
    return axis == 0 ? face.point(along, across) : face.point(across, along);
  };
  const double lo = axis == 0 ? b.u_min : b.v_min, hi = axis == 0 ? b.u_max : b.v_max;
  const double a0 = axis == 0 ? b.v_min : b.u_min, a1 = axis == 0 ? b.v_max : b.u_max;
  double seam_length = 0;
  Vec3 previous = Vec3::Zero();  // (read from the second point on)
  for (int i = 0; i <= n; ++i) {
    const double t = a0 + (a1 - a0) * i / n;
    const Vec3 side = at(lo, t);
    if (!((side - at(hi, t)).norm() <= tiny)) return false;
    if (i > 0) seam_length += (side - previous).norm();
    previous = side;
  }
  return seam_length > tiny;
}

}  // namespace

void join_seam_sides(const SurfaceFace& face, PanelMesh& mesh) {
  const bool periodic = closed_round_a_seam(face);
  // A face closed on itself (not periodic): its seam joined as a period's.
  const bool on_itself[2] = {!periodic && closed_on_itself(face, 0),
                             !periodic && closed_on_itself(face, 1)};
  if (!periodic && !on_itself[0] && !on_itself[1]) return;
  weld_coincident_vertices(mesh, 1e-9 * face.model_size());
  const UvBounds b = face.bounds();
  if (!periodic) {
    if (on_itself[0]) join_along(mesh, 0, b.u_min, b.u_max - b.u_min);
    if (on_itself[1]) join_along(mesh, 1, b.v_min, b.v_max - b.v_min);
    return;
  }
  // Each seam's looseness measured once: it welds, and a loose seam's far
  // copy is the face's own bound.
  const LooseSeam seams[2] = {loose_seam(face, 0), loose_seam(face, 1)};
  weld_loose_seams(face, mesh, seams);
  if (spans_period(face.u_periodic(), b.u_min, b.u_max, face.u_period()))
    join_along(mesh, 0, b.u_min, face.u_period() + seams[0].hair);
  if (spans_period(face.v_periodic(), b.v_min, b.v_max, face.v_period()))
    join_along(mesh, 1, b.v_min, face.v_period() + seams[1].hair);
}

}  // namespace tessella
