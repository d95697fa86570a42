#include "tessella/nest.h"

#include <algorithm>
#include <clipper.hpp>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>
#include <tuple>

#include "tessella/errors.h"

namespace tessella {

namespace {

constexpr double kPi = 3.14159265358979323846;

double cross(const Vec2& o, const Vec2& a, const Vec2& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

// One allowed orientation of a part: its hull and bounding box.
struct Pose {
  double angle_deg = 0;
  std::vector<Vec2> hull;
  std::vector<Vec2> reflected;  // -hull, counter-clockwise too
  double min_x = 0, max_x = 0, min_y = 0, max_y = 0;
};

Pose make_pose(const std::vector<Vec2>& outline, double angle_deg) {
  Pose pose;
  pose.angle_deg = angle_deg;
  const double a = angle_deg * kPi / 180.0, c = std::cos(a), s = std::sin(a);
  std::vector<Vec2> rotated;
  for (const Vec2& p : outline) rotated.emplace_back(c * p.x() - s * p.y(), s * p.x() + c * p.y());
  pose.hull = convex_hull(rotated);
  for (const Vec2& p : pose.hull) pose.reflected.push_back(-p);
  pose.min_x = pose.max_x = pose.hull[0].x();
  pose.min_y = pose.max_y = pose.hull[0].y();
  for (const Vec2& p : pose.hull) {
    pose.min_x = std::min(pose.min_x, p.x()), pose.max_x = std::max(pose.max_x, p.x());
    pose.min_y = std::min(pose.min_y, p.y()), pose.max_y = std::max(pose.max_y, p.y());
  }
  return pose;
}

// Hull grown by at least `r` everywhere (Minkowski sum with an 8-gon around the circle).
std::vector<Vec2> grow(const std::vector<Vec2>& hull, double r) {
  if (r <= 0) return hull;
  const int m = 8;
  const double rr = r / std::cos(kPi / m);
  std::vector<Vec2> pts;
  for (const Vec2& p : hull)
    for (int k = 0; k < m; ++k) {
      const double a = 2 * kPi * k / m;
      pts.emplace_back(p.x() + rr * std::cos(a), p.y() + rr * std::sin(a));
    }
  return convex_hull(pts);
}

// Minkowski sum of two convex counter-clockwise polygons by merging their
// edges in angle order: O(n + m).
std::vector<Vec2> minkowski_convex(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  auto lowest = [](const std::vector<Vec2>& p) {
    std::size_t k = 0;
    for (std::size_t i = 1; i < p.size(); ++i)
      if (std::tie(p[i].y(), p[i].x()) < std::tie(p[k].y(), p[k].x())) k = i;
    return k;
  };
  const std::size_t n = a.size(), m = b.size();
  std::size_t i0 = lowest(a), j0 = lowest(b), i = 0, j = 0;
  std::vector<Vec2> out;
  out.reserve(n + m);
  while (i < n || j < m) {
    out.push_back(a[(i0 + i) % n] + b[(j0 + j) % m]);
    const Vec2 ea = a[(i0 + i + 1) % n] - a[(i0 + i) % n];
    const Vec2 eb = b[(j0 + j + 1) % m] - b[(j0 + j) % m];
    const double c = ea.x() * eb.y() - ea.y() * eb.x();
    if (j >= m || (i < n && c > 0)) {
      ++i;
    } else if (i >= n || c < 0) {
      ++j;
    } else {
      ++i, ++j;
    }
  }
  return out;
}

ClipperLib::Path to_path(const std::vector<Vec2>& poly, double scale) {
  ClipperLib::Path path;
  for (const Vec2& p : poly)
    path.emplace_back(static_cast<ClipperLib::cInt>(std::llround(p.x() * scale)),
                      static_cast<ClipperLib::cInt>(std::llround(p.y() * scale)));
  return path;
}

struct Inner {  // integer rectangle of allowed reference points (empty if x0 > x1)
  long long x0, y0, x1, y1;
};

Inner inner_fit(const Pose& pose, const NestParams& p, double scale) {
  Inner r;
  r.x0 = static_cast<long long>(std::ceil((p.margin - pose.min_x) * scale));
  r.x1 = static_cast<long long>(std::floor((p.sheet_width - p.margin - pose.max_x) * scale));
  r.y0 = static_cast<long long>(std::ceil((p.margin - pose.min_y) * scale));
  r.y1 = static_cast<long long>(std::floor((p.sheet_height - p.margin - pose.max_y) * scale));
  return r;
}

bool fits(const Inner& r) { return r.x0 <= r.x1 && r.y0 <= r.y1; }

// Placement rules tried in turn; the layout with the fewest sheets (then the
// smallest used box on its last sheet) wins.
enum class Rule { BottomLeft, LeftBottom };

struct Candidate {
  bool found = false;
  double top = 0, left = 0, right = 0;
  int rotation = 0;
  long long x = 0, y = 0;
  bool better_than(const Candidate& o, Rule rule) const {
    if (!o.found) return true;
    if (rule == Rule::BottomLeft)
      return std::tie(top, left, rotation) < std::tie(o.top, o.left, o.rotation);
    return std::tie(right, top, rotation) < std::tie(o.right, o.top, o.rotation);
  }
};

}  // namespace

std::vector<Vec2> convex_hull(std::vector<Vec2> pts) {
  std::sort(pts.begin(), pts.end(), [](const Vec2& a, const Vec2& b) {
    return std::tie(a.x(), a.y()) < std::tie(b.x(), b.y());
  });
  pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
  if (pts.size() < 3) return pts;
  std::vector<Vec2> h(2 * pts.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], pts[i]) <= 0) --k;
    h[k++] = pts[i];
  }
  for (std::size_t i = pts.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(h[k - 2], h[k - 1], pts[i]) <= 0) --k;
    h[k++] = pts[i];
  }
  h.resize(k - 1);
  return h;
}

double polygon_area(const std::vector<Vec2>& poly) {
  double a = 0;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Vec2& p = poly[i];
    const Vec2& q = poly[(i + 1) % poly.size()];
    a += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * a;
}

NestLayout nest_parts(const std::vector<std::vector<Vec2>>& outlines, const NestParams& params,
                      const std::vector<std::string>& names) {
  require_in_range("sheet_width (mm)", params.sheet_width, 1e-3, 1e7);
  require_in_range("sheet_height (mm)", params.sheet_height, 1e-3, 1e7);
  require_in_range("margin (mm)", params.margin, 0.0, 1e7);
  require_in_range("spacing (mm)", params.spacing, 0.0, 1e7);
  require_in_range("rotations", params.rotations, 1, 360);
  require_in_range("resolution (mm)", params.resolution, 1e-6, 1.0);
  require_in_range("max_sheets", params.max_sheets, 1, 1e6);
  if (2 * params.margin >= std::min(params.sheet_width, params.sheet_height))
    throw InvalidParameter("margin (mm) must be less than half the sheet's smaller side");
  if (!names.empty() && names.size() != outlines.size())
    throw InvalidParameter("names must be empty or one per part");
  const double scale = 1.0 / params.resolution;
  // Parts may touch the grown hulls; grow a few grid steps more so rounding
  // never lets two parts come closer than `spacing`.
  const double grow_by = params.spacing + 3.0 * params.resolution;
  auto name = [&](std::size_t i) { return names.empty() ? "part " + std::to_string(i) : names[i]; };

  const std::size_t n = outlines.size();
  std::vector<std::vector<Pose>> poses(n);
  std::vector<double> area(n), hull_area(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto& o = outlines[i];
    if (o.size() < 3) throw InvalidParameter(name(i) + ": an outline needs at least 3 points");
    for (const Vec2& p : o)
      if (!p.allFinite()) throw InvalidParameter(name(i) + ": outline has a non-finite point");
    area[i] = std::abs(polygon_area(o));
    bool any = false;
    for (int k = 0; k < params.rotations; ++k) {
      poses[i].push_back(make_pose(o, 360.0 * k / params.rotations));
      if (poses[i].back().hull.size() < 3)
        throw InvalidParameter(name(i) + ": outline has no area");
      any = any || fits(inner_fit(poses[i].back(), params, scale));
    }
    hull_area[i] = polygon_area(poses[i][0].hull);
    if (!any) {
      std::ostringstream msg;
      msg << name(i) << " (" << poses[i][0].max_x - poses[i][0].min_x << " x "
          << poses[i][0].max_y - poses[i][0].min_y << " mm) does not fit on the sheet "
          << params.sheet_width << " x " << params.sheet_height << " mm with margin "
          << params.margin << " mm in any of the " << params.rotations << " allowed rotations";
      throw InvalidParameter(msg.str());
    }
  }

  // Largest first; ties by input order (deterministic).
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return hull_area[a] > hull_area[b]; });

  auto run = [&](Rule rule, double& last_box) {
    NestLayout layout;
    layout.placements.resize(n);
    std::vector<std::vector<std::vector<Vec2>>> sheets;  // grown hulls placed, per sheet
    std::vector<double> failed_area;  // per sheet: smallest hull area that found no room

    auto best_on = [&](std::size_t i, const std::vector<std::vector<Vec2>>& placed) {
      Candidate best;
      for (int k = 0; k < params.rotations; ++k) {
        const Pose& pose = poses[i][k];
        const Inner r = inner_fit(pose, params, scale);
        if (!fits(r)) continue;
        ClipperLib::Path rect{{r.x0, r.y0}, {r.x1, r.y0}, {r.x1, r.y1}, {r.x0, r.y1}};
        ClipperLib::Paths free_region;
        if (placed.empty()) {
          free_region.push_back(rect);
        } else {
          ClipperLib::Paths nfps;
          for (const auto& a : placed) {
            nfps.push_back(to_path(minkowski_convex(a, pose.reflected), scale));
          }
          ClipperLib::Clipper c;
          c.AddPath(rect, ClipperLib::ptSubject, true);
          c.AddPaths(nfps, ClipperLib::ptClip, true);
          c.Execute(ClipperLib::ctDifference, free_region, ClipperLib::pftNonZero,
                    ClipperLib::pftNonZero);
        }
        for (const auto& path : free_region)
          for (const auto& q : path) {
            Candidate cand;
            cand.found = true;
            cand.rotation = k;
            cand.x = q.X, cand.y = q.Y;
            cand.top = q.Y / scale + pose.max_y;
            cand.left = q.X / scale + pose.min_x;
            cand.right = q.X / scale + pose.max_x;
            if (cand.better_than(best, rule)) best = cand;
          }
      }
      return best;
    };

    for (std::size_t i : order) {
      Candidate best;
      int sheet = -1;
      for (std::size_t s = 0; s < sheets.size() && !best.found; ++s) {
        // A sheet where a part at most 1% larger found no room is skipped
        // (saves most of the time once sheets fill; a heuristic, never unsafe).
        if (failed_area[s] <= 1.01 * hull_area[i]) continue;
        best = best_on(i, sheets[s]);
        if (best.found) {
          sheet = static_cast<int>(s);
        } else {
          failed_area[s] = std::min(failed_area[s], hull_area[i]);
        }
      }
      if (!best.found) {
        if (static_cast<int>(sheets.size()) >= params.max_sheets)
          throw LimitExceeded("nesting needs more than max_sheets (" +
                              std::to_string(params.max_sheets) + ") sheets");
        sheets.emplace_back();
        failed_area.push_back(std::numeric_limits<double>::infinity());
        sheet = static_cast<int>(sheets.size()) - 1;
        best = best_on(i, sheets.back());
        if (!best.found) throw GeometryFailure("nesting: a part that fits found no place");
      }
      const Pose& pose = poses[i][best.rotation];
      const Vec2 offset(best.x / scale, best.y / scale);
      std::vector<Vec2> hull = pose.hull;
      for (Vec2& p : hull) p += offset;
      sheets[sheet].push_back(grow(hull, grow_by));
      layout.placements[i] = {sheet, pose.angle_deg, offset};
    }

    layout.sheet_count = static_cast<int>(sheets.size());
    layout.sheet_utilization.assign(sheets.size(), 0.0);
    const double sheet_area = params.sheet_width * params.sheet_height;
    double total = 0;
    for (std::size_t i = 0; i < n; ++i) {
      layout.sheet_utilization[layout.placements[i].sheet] += area[i] / sheet_area;
      total += area[i];
    }
    layout.utilization = sheets.empty() ? 0.0 : total / (sheet_area * sheets.size());
    // used box of the last sheet (what a better layout leaves free)
    double x1 = 0, y1 = 0;
    if (!sheets.empty())
      for (const auto& h : sheets.back())
        for (const Vec2& q : h) x1 = std::max(x1, q.x()), y1 = std::max(y1, q.y());
    last_box = x1 * y1;
    return layout;
  };

  double box_a = 0, box_b = 0;
  NestLayout a = run(Rule::BottomLeft, box_a);
  NestLayout b = run(Rule::LeftBottom, box_b);
  if (b.sheet_count < a.sheet_count || (b.sheet_count == a.sheet_count && box_b < box_a)) return b;
  return a;
}

}  // namespace tessella
