#include "methods/agents/agent_walk.h"

#include <algorithm>
#include <cmath>

#include "geometry/trim_deflection.h"
#include "tessella/errors.h"

namespace tessella::agents {

double path_deviation(const SurfaceFace& face, const Vec2& qa, const Vec2& qb, const Vec3& pa,
                      const Vec3& pb) {
  const Vec3 chord = pb - pa;
  const double length = chord.norm();
  const Vec3 c = 0.5 * (pa + pb);
  const Vec2 qm = 0.5 * (qa + qb);
  const Vec3 pm = face.point(qm.x(), qm.y());
  if (length <= 0) return (pm - c).norm();
  const Vec3 d = chord / length;
  // Position along the chord, 0 at the middle, per unit of path parameter
  // t in [-1/2, 1/2]: on average `length`.
  const double t = std::clamp(-(pm - c).dot(d) / length, -0.25, 0.25);
  const Vec2 q = qm + t * (qb - qa);
  const Vec3 p = face.point(q.x(), q.y());
  // Both are surface points near the middle: the one closer to the normal
  // plane through c gives the sagitta (never report less than the plane
  // distance allows).
  const double off_m = std::abs((pm - c).dot(d)), off_p = std::abs((p - c).dot(d));
  const Vec3& best = off_p < off_m ? p : pm;
  return (best - c - (best - c).dot(d) * d).norm();
}

UvTrimClassifier agent_trim(const SurfaceFace& face) {
  return UvTrimClassifier(face.trim_loops(steering_trim_deflection(face)));
}

std::vector<double> row_crossings(const SurfaceFace& face, const UvTrimClassifier& trim, int dir,
                                  double c) {
  const UvBounds b = face.bounds();
  const double lo = dir == 0 ? b.v_min : b.u_min;
  const double hi = dir == 0 ? b.v_max : b.u_max;
  const double eps = 1e-7 * (hi - lo);
  return trim.crossings(dir, std::clamp(c, lo + eps, hi - eps));
}

RowAgents::RowAgents(const SurfaceFace& face, const UvTrimClassifier& trim, int dir,
                     std::vector<double> rows)
    : face_(face), dir_(dir), rows_(std::move(rows)) {
  for (double c : rows_) crossings_.push_back(row_crossings(face, trim, dir, c));
  origin_points_.resize(rows_.size());
}

bool RowAgents::row_inside(std::size_t r, double s) const {
  const std::vector<double>& x = crossings_[r];
  return (std::lower_bound(x.begin(), x.end(), s) - x.begin()) % 2 == 1;
}

Vec3 RowAgents::eval(std::size_t r, double s) const {
  return dir_ == 0 ? face_.point(s, rows_[r]) : face_.point(rows_[r], s);
}

RowAgents::Probe RowAgents::probe(double a, double b) {
  if (!origin_valid_ || origin_ != a) {
    for (std::size_t r = 0; r < rows_.size(); ++r) origin_points_[r] = eval(r, a);
    origin_ = a;
    origin_valid_ = true;
  }
  Probe p;
  const double m = 0.5 * (a + b);
  for (std::size_t r = 0; r < rows_.size(); ++r) {
    if (!row_inside(r, a) && !row_inside(r, m) && !row_inside(r, b)) continue;
    const Vec3 pb = eval(r, b);
    const Vec2 qa = dir_ == 0 ? Vec2(a, rows_[r]) : Vec2(rows_[r], a);
    const Vec2 qb = dir_ == 0 ? Vec2(b, rows_[r]) : Vec2(rows_[r], b);
    p.deviation = std::max(p.deviation, path_deviation(face_, qa, qb, origin_points_[r], pb));
    p.length = std::max(p.length, (pb - origin_points_[r]).norm());
  }
  return p;
}

std::vector<double> even_rows(double lo, double hi, int count) {
  std::vector<double> rows(count + 1);
  for (int k = 0; k <= count; ++k) rows[k] = lo + (hi - lo) * k / count;
  rows.back() = hi;
  return rows;
}

std::vector<double> walk(double s0, double s1, double step,
                         const std::function<bool(double, double)>& ok) {
  std::vector<double> nodes{s0};
  const double span = std::abs(s1 - s0);
  if (span <= 0) return nodes;
  const double dir = s1 > s0 ? 1.0 : -1.0;
  auto clamp_end = [&](double b) { return dir > 0 ? std::min(b, s1) : std::max(b, s1); };
  const double finest = 1e-9 * span;
  double a = s0;
  while (std::abs(s1 - a) > finest) {
    // Grow the edge a sample step at a time while the rules hold.
    double b = clamp_end(a + dir * step);
    bool good = ok(a, b);
    while (good && b != s1) {
      b = clamp_end(b + dir * step);
      good = ok(a, b);
    }
    if (!good) {
      // Past the limit: step back by a tenth of a step until the rules hold
      // (below a tenth, halve: the sample step was too coarse there).
      double back = 0.1 * step;
      while (!good) {
        if (std::abs(b - a) > back * (1 + 1e-9)) {
          b -= dir * back;
        } else {
          back = 0.5 * std::abs(b - a);
          if (back < finest) break;  // cannot get shorter: accept
          b = a + dir * back;
        }
        good = ok(a, b);
      }
    }
    nodes.push_back(b);
    a = b;
  }
  nodes.back() = s1;
  // A last edge much shorter than the one before: share the two evenly when
  // both halves keep the rules.
  const std::size_t n = nodes.size();
  if (n >= 3) {
    const double last = std::abs(nodes[n - 1] - nodes[n - 2]);
    const double before = std::abs(nodes[n - 2] - nodes[n - 3]);
    if (last < 0.3 * before) {
      const double mid = 0.5 * (nodes[n - 3] + nodes[n - 1]);
      if (ok(nodes[n - 3], mid) && ok(mid, nodes[n - 1])) nodes[n - 2] = mid;
    }
  }
  return nodes;
}

std::vector<double> gradient_walk(double s0, double s1, double first, double min_step,
                                  double max_step, double target,
                                  const std::function<double(double, double)>& deviation) {
  std::vector<double> nodes{s0};
  const double span = std::abs(s1 - s0);
  if (span <= 0) return nodes;
  const double dir = s1 > s0 ? 1.0 : -1.0;
  auto clamp_end = [&](double b) { return dir > 0 ? std::min(b, s1) : std::max(b, s1); };
  double a = s0;
  double S1 = 0, S2 = 0, E1 = 0, E2 = 0;
  double step = first;  // the first step is taken arbitrarily
  while (std::abs(s1 - a) > 1e-9 * span) {
    const double b = clamp_end(a + dir * step);
    const double e = deviation(a, b);
    nodes.push_back(b);
    S2 = S1, E2 = E1;
    S1 = std::abs(b - a), E1 = e;
    a = b;
    // Thesis 5.2: step_a / dev = (step_{a-1} + step_{a-2}) / (dev_{a-1} + dev_{a-2}).
    step = (E1 + E2) > 0 ? target * (S1 + S2) / (E1 + E2) : max_step;
    step = std::clamp(step, min_step, max_step);
  }
  nodes.back() = s1;
  return nodes;
}

std::vector<double> merge_walks(std::vector<double> a, std::vector<double> b) {
  a.insert(a.end(), b.begin(), b.end());
  std::sort(a.begin(), a.end());
  a.erase(std::unique(a.begin(), a.end()), a.end());
  return a;
}

StartSpec parse_start(const std::string& start) {
  StartSpec s;
  if (start == "max_curvature") {
    s.max_curvature = true;
  } else if (start == "u_min_v_min") {
  } else if (start == "u_max_v_min") {
    s.u_from_min = false;
  } else if (start == "u_min_v_max") {
    s.v_from_min = false;
  } else if (start == "u_max_v_max") {
    s.u_from_min = s.v_from_min = false;
  } else {
    throw InvalidParameter(
        "start must be one of u_min_v_min, u_max_v_min, u_min_v_max, u_max_v_max, "
        "max_curvature, got '" +
        start + "'");
  }
  return s;
}

Vec2 max_curvature_point(const SurfaceFace& face, const UvTrimClassifier& trim,
                         double sample_step) {
  const UvBounds b = face.bounds();
  const int n = std::max(2, static_cast<int>(std::ceil(1.0 / sample_step)));
  const double hu = (b.u_max - b.u_min) / n, hv = (b.v_max - b.v_min) / n;
  Vec2 best(0.5 * (b.u_min + b.u_max), 0.5 * (b.v_min + b.v_max));
  double best_dev = -1;
  for (int j = 0; j <= n; ++j) {
    const double v = b.v_min + hv * j;
    const std::vector<double> x = row_crossings(face, trim, 0, v);
    for (int i = 0; i <= n; ++i) {
      const double u = b.u_min + hu * i;
      if ((std::lower_bound(x.begin(), x.end(), u) - x.begin()) % 2 == 0) continue;
      const double u0 = std::max(b.u_min, u - hu), u1 = std::min(b.u_max, u + hu);
      const double v0 = std::max(b.v_min, v - hv), v1 = std::min(b.v_max, v + hv);
      const Vec3 c = face.point(u, v);
      const double du = chord_deviation(face.point(u0, v), face.point(u1, v), c);
      const double dv = chord_deviation(face.point(u, v0), face.point(u, v1), c);
      // Deviation per squared chord length: curvature, not just size.
      const double lu = (face.point(u1, v) - face.point(u0, v)).squaredNorm();
      const double lv = (face.point(u, v1) - face.point(u, v0)).squaredNorm();
      const double k = std::max(lu > 0 ? du / lu : 0.0, lv > 0 ? dv / lv : 0.0);
      if (k > best_dev) best_dev = k, best = Vec2(u, v);
    }
  }
  return best;
}

}  // namespace tessella::agents
