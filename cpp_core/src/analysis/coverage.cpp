#include "analysis/coverage.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include "common/parallel_chunks.h"
#include "geometry/trim_deflection.h"
#include "mesh/seam_sides.h"
#include "tessella/errors.h"
#include "tessella/progress.h"

namespace tessella {

namespace {

// One crossing of a scanline by an edge of polygon `owner` (-1: a trim loop).
struct Crossing {
  int owner;
  double x;
};

// Scanlines of constant y (y = v for dir 0, u for dir 1) at the middles of
// `rows` equal strips of [lo, hi].
struct Rows {
  double lo = 0, h = 1;
  int count = 0;
  double at(int r) const { return lo + (r + 0.5) * h; }
};

// Adds the crossings of edge a-b with every scanline under the half-open rule
// (a scanline through a vertex counts once). The edge is ordered canonically
// first, so two panels sharing it compute the same x bit for bit.
void add_edge(const Rows& rows, Vec2 a, Vec2 b, int owner,
              std::vector<std::vector<Crossing>>& out) {
  if (a.y() == b.y()) return;
  if (b.y() < a.y() || (b.y() == a.y() && b.x() < a.x())) std::swap(a, b);
  // One row early: the rounding of the division may skip a row whose middle
  // lies exactly on a.y (the test below decides).
  int r0 = static_cast<int>(std::ceil((a.y() - rows.lo) / rows.h - 0.5)) - 1;
  r0 = std::max(r0, 0);
  for (int r = r0; r < rows.count; ++r) {
    const double y = rows.at(r);
    if (y < a.y()) continue;
    if (y >= b.y()) break;
    const double x = a.x() + (y - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
    out[static_cast<std::size_t>(r)].push_back({owner, x});
  }
}

struct Event {
  double x;
  int delta;   // panel count change
  int toggle;  // 1: the inside-the-trims flag flips here
  bool operator<(const Event& o) const {
    if (x != o.x) return x < o.x;
    if (delta != o.delta) return delta < o.delta;
    return toggle < o.toggle;
  }
};

// Gap, overlap and outside area for scanlines of constant coordinate `dir`
// (0: v = const, x = u; 1: u = const, x = v).
Coverage scan(const SurfaceFace& face, const std::vector<std::vector<Vec2>>& panels,
              const std::vector<TrimLoop>& loops, int dir, int count) {
  auto swap_xy = [dir](const Vec2& p) { return dir == 0 ? p : Vec2(p.y(), p.x()); };
  // Rows over the face and the panels (a panel outside the face is counted).
  double lo = 1e300, hi = -1e300;
  auto extend = [&](const Vec2& p) {
    const double y = swap_xy(p).y();
    lo = std::min(lo, y), hi = std::max(hi, y);
  };
  for (const auto& l : loops)
    for (const Vec2& p : l.uv) extend(p);
  for (const auto& poly : panels)
    for (const Vec2& p : poly) extend(p);
  Coverage c;
  if (!(hi > lo)) return c;
  Rows rows{lo, (hi - lo) / count, count};

  std::vector<std::vector<Crossing>> crossings(static_cast<std::size_t>(count));
  for (const auto& l : loops)
    for (std::size_t k = 0; k < l.uv.size(); ++k)
      add_edge(rows, swap_xy(l.uv[k]), swap_xy(l.uv[(k + 1) % l.uv.size()]), -1, crossings);
  for (std::size_t p = 0; p < panels.size(); ++p) {
    const auto& q = panels[p];
    for (std::size_t k = 0; k < q.size(); ++k)
      add_edge(rows, swap_xy(q[k]), swap_xy(q[(k + 1) % q.size()]), static_cast<int>(p), crossings);
  }

  auto area_element = [&](double x, double y) {
    const Vec2 uv = swap_xy(Vec2(x, y));
    const SurfacePoint sp = face.derivatives(uv.x(), uv.y());
    return sp.du.cross(sp.dv).norm();
  };
  std::vector<Event> events;
  for (int r = 0; r < count; ++r) {
    if (r % 64 == 0) report_progress(double(r) / count, "checking coverage");
    auto& row = crossings[static_cast<std::size_t>(r)];
    if (row.empty()) continue;
    // Per owner, consecutive crossings pair into inside intervals (even-odd).
    std::stable_sort(row.begin(), row.end(), [](const Crossing& a, const Crossing& b) {
      return a.owner != b.owner ? a.owner < b.owner : a.x < b.x;
    });
    events.clear();
    for (std::size_t i = 0; i + 1 < row.size(); ++i) {
      if (row[i].owner != row[i + 1].owner) continue;
      if (row[i].owner < 0) {
        events.push_back({row[i].x, 0, 1});
        events.push_back({row[i + 1].x, 0, 1});
      } else {
        events.push_back({row[i].x, +1, 0});
        events.push_back({row[i + 1].x, -1, 0});
      }
      ++i;
    }
    std::sort(events.begin(), events.end());
    const double y = rows.at(r);
    int panels_here = 0;
    bool inside = false;
    for (std::size_t i = 0; i < events.size(); ++i) {
      panels_here += events[i].delta;
      if (events[i].toggle) inside = !inside;
      if (i + 1 == events.size()) break;
      const double x0 = events[i].x, x1 = events[i + 1].x;
      if (!(x1 > x0)) continue;
      const bool gap = inside && panels_here == 0;
      const int extra = std::max(0, panels_here - 1);
      const bool out = !inside && panels_here > 0;
      if (!gap && !extra && !out) continue;
      const double xm = 0.5 * (x0 + x1);
      const double piece = (x1 - x0) * rows.h * area_element(xm, y);
      if (gap) {
        c.gap += piece;
        // Length along the scanline on the surface (chord of the two ends).
        const Vec2 a = swap_xy(Vec2(x0, y)), b = swap_xy(Vec2(x1, y));
        const double width = (face.point(a.x(), a.y()) - face.point(b.x(), b.y())).norm();
        if (width > c.widest_gap) {
          const Vec2 m = swap_xy(Vec2(xm, y));
          c.widest_gap = width;
          c.widest_gap_at = face.point(m.x(), m.y());
        }
      }
      c.overlap += extra * piece;
      if (out) c.outside += panels_here * piece;
    }
  }
  return c;
}

// The first thing wrong with the coverage, or "". deviation_band < 0: no 3D
// confirmation (the caller has no deviations).
std::string coverage_problem(const Coverage& c, double deviation_band, const std::string& method) {
  if (!(c.face_area > 0)) return "";
  char buf[400];
  if (c.gap_fraction() > kMaxCoverageError) {
    std::snprintf(buf, sizeof buf,
                  "%s: the panels leave %.2f%% of the face uncovered (the widest hole, "
                  "%.1f mm across, is near (%.1f, %.1f, %.1f))",
                  method.c_str(), 100.0 * c.gap_fraction(), c.widest_gap, c.widest_gap_at.x(),
                  c.widest_gap_at.y(), c.widest_gap_at.z());
    return buf;
  }
  if (c.overlap_fraction() > kMaxCoverageError) {
    std::snprintf(buf, sizeof buf,
                  "%s: panels overlap or reach outside the face's trims over %.2f%% of "
                  "the face area",
                  method.c_str(), 100.0 * c.overlap_fraction());
    return buf;
  }
  // 3D confirmation: flat or bilinear panels are no larger than the surface
  // they stand for, but for their deviation band.
  if (deviation_band >= 0 &&
      c.model_area > c.covered_area + deviation_band + kMaxCoverageError * c.face_area) {
    std::snprintf(buf, sizeof buf,
                  "%s: the panels' 3D area is %.4f x the face area, more than their (u,v) "
                  "outlines cover (%.4f x): panels overlap in space",
                  method.c_str(), c.model_area / c.face_area, c.covered_area / c.face_area);
    return buf;
  }
  return "";
}

// A panel's region in (u,v). A corner at a pole (a point where the surface
// degenerates along u or v: all of an iso-line maps to one point) stands for
// the stretch of that iso-line between its neighbours' parameters, so it is
// replaced by the two ends of that stretch: the pole triangle of a sphere
// covers its whole cell in (u,v), not half of it.
std::vector<Vec2> region_outline(const SurfaceFace& face, const std::vector<Vec2>& q) {
  std::vector<Vec2> out;
  const std::size_t n = q.size();
  for (std::size_t k = 0; k < n; ++k) {
    const SurfacePoint d = face.derivatives(q[k].x(), q[k].y());
    const double du = d.du.norm(), dv = d.dv.norm();
    const Vec2& prev = q[(k + n - 1) % n];
    const Vec2& next = q[(k + 1) % n];
    if (du <= 1e-9 * dv) {
      out.emplace_back(prev.x(), q[k].y());
      out.emplace_back(next.x(), q[k].y());
    } else if (dv <= 1e-9 * du) {
      out.emplace_back(q[k].x(), prev.y());
      out.emplace_back(q[k].x(), next.y());
    } else {
      out.push_back(q[k]);
    }
  }
  return out;
}

// Along a direction the face spans a whole period of (a full cylinder, a
// dome), a panel beside the seam may have corners on both sides of it (a
// merge moved a seam node off the seam, or a vertex on the seam has one (u,v)
// for both sides): its corners are unwrapped into one run before the pole
// substitution (seam_shift: rounding at half a period collapsed a cylinder
// cut in two), and the region is then cut into the period's strip with its
// shifted copies.
void unwrap(std::vector<Vec2>& q, int axis, double period) {
  for (std::size_t k = 1; k < q.size(); ++k)
    q[k][axis] += seam_shift(q[k - 1][axis], q[k][axis], period);
}

// The part of polygon q with lo <= coordinate `axis` <= hi (Sutherland-Hodgman).
std::vector<Vec2> clip_to_strip(const std::vector<Vec2>& q, int axis, double lo, double hi) {
  auto clip = [axis](const std::vector<Vec2>& in, double bound, double sign) {
    std::vector<Vec2> out;
    for (std::size_t k = 0; k < in.size(); ++k) {
      const Vec2& a = in[k];
      const Vec2& b = in[(k + 1) % in.size()];
      const double da = sign * (a[axis] - bound), db = sign * (b[axis] - bound);
      if (da >= 0) out.push_back(a);
      if ((da >= 0) != (db >= 0)) out.push_back(a + (da / (da - db)) * (b - a));
    }
    return out;
  };
  return clip(clip(q, lo, 1.0), hi, -1.0);
}

std::vector<std::vector<Vec2>> panel_regions(const SurfaceFace& face, std::vector<Vec2> q) {
  const UvBounds b = face.bounds();
  const bool wrap[2] = {closed_along(face, 0), closed_along(face, 1)};
  const double period[2] = {face.u_period(), face.v_period()};
  const double lo[2] = {b.u_min, b.v_min}, hi[2] = {b.u_max, b.v_max};
  for (int axis = 0; axis < 2; ++axis)
    if (wrap[axis]) unwrap(q, axis, period[axis]);
  std::vector<std::vector<Vec2>> regions{region_outline(face, q)};
  for (int axis = 0; axis < 2; ++axis) {
    if (!wrap[axis]) continue;
    std::vector<std::vector<Vec2>> cut;
    for (const auto& r : regions) {
      double a = r[0][axis], z = a;
      for (const Vec2& x : r) a = std::min(a, x[axis]), z = std::max(z, x[axis]);
      const double eps = 1e-12 * period[axis];
      if (a >= lo[axis] - eps && z <= hi[axis] + eps) {
        cut.push_back(r);
        continue;
      }
      for (int shift = -1; shift <= 1; ++shift) {
        std::vector<Vec2> moved = r;
        for (Vec2& x : moved) x[axis] += shift * period[axis];
        std::vector<Vec2> piece = clip_to_strip(moved, axis, lo[axis], hi[axis]);
        if (piece.size() >= 3) cut.push_back(std::move(piece));
      }
    }
    regions = std::move(cut);
  }
  return regions;
}

}  // namespace

Coverage measure_coverage(const SurfaceFace& face, const PanelMesh& mesh,
                          const std::vector<double>& panel_areas, const CoverageParams& params) {
  std::vector<std::vector<Vec2>> panels;
  panels.reserve(mesh.panels.size());
  for (std::size_t p = 0; p < mesh.panels.size(); ++p)
    for (auto& region : panel_regions(face, panel_corner_uv(mesh, p)))
      panels.push_back(std::move(region));
  const std::vector<TrimLoop> loops =
      face.trim_loops(trim_deflection(face, params.trim_deflection));
  int count = params.rows;
  if (count <= 0) {
    count = static_cast<int>(4.0 * std::sqrt(double(std::max<std::size_t>(1, panels.size()))));
    count = std::clamp(count, 256, 4096);
  }
  // The two scans on two threads where there are two (a worker evaluates
  // in a scope of its own exactly where the caller does, so the figures are
  // the same bit for bit).
  Coverage both[2];
  const bool scoped = SurfaceFace::FastEvaluation::active(face);
  ChunkQueue directions(2, 1);
  run_chunks(directions, worker_threads(), [&](bool calling) {
    std::optional<SurfaceFace::FastEvaluation> fast;
    if (!calling && scoped) fast.emplace(face, true);
    std::size_t begin = 0, end = 0;
    while (directions.next(begin, end)) both[begin] = scan(face, panels, loops, int(begin), count);
  });
  Coverage c = both[0];
  const Coverage& other = both[1];
  c.gap = std::max(c.gap, other.gap);
  c.overlap = std::max(c.overlap, other.overlap);
  c.outside = std::max(c.outside, other.outside);
  if (other.widest_gap > c.widest_gap) {
    c.widest_gap = other.widest_gap;
    c.widest_gap_at = other.widest_gap_at;
  }
  c.face_area = face.area();
  // What the panels cover on the surface, by the scans (the face's own area
  // is OCCT's exact integral).
  c.covered_area = c.face_area - c.gap + c.overlap + c.outside;
  for (double a : panel_areas)
    if (std::isfinite(a)) c.model_area += a;
  return c;
}

std::string coverage_message(const Coverage& c, const std::string& method) {
  return coverage_problem(c, -1.0, method);
}

void check_coverage(const Coverage& c, double deviation_band, const std::string& method) {
  const std::string problem = coverage_problem(c, deviation_band, method);
  if (!problem.empty()) throw GeometryFailure(problem);
}

}  // namespace tessella
