#include "analysis/deviation_bound.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tessella {

namespace {

// One choice of a surface point per corner: parameters and points.
template <std::size_t N>
struct Choice {
  std::array<Vec2, N> f;
  std::array<Vec3, N> s;
};

// The box of the corners' parameters.
template <std::size_t N>
UvBounds box_of(const std::array<Vec2, N>& f) {
  UvBounds box{f[0].x(), f[0].x(), f[0].y(), f[0].y()};
  for (const Vec2& q : f) {
    box.u_min = std::min(box.u_min, q.x()), box.u_max = std::max(box.u_max, q.x());
    box.v_min = std::min(box.v_min, q.y()), box.v_max = std::max(box.v_max, q.y());
  }
  return box;
}

// The parameters with a periodic direction unwrapped next to the first
// corner's (S is periodic, so S(f) is unchanged), and their box.
template <std::size_t N>
UvBounds unwrap(const SurfaceFace& face, std::array<Vec2, N>& f) {
  for (std::size_t k = 1; k < N; ++k) {
    if (face.u_periodic()) {
      const double p = face.u_period();
      f[k].x() -= p * std::round((f[k].x() - f[0].x()) / p);
    }
    if (face.v_periodic()) {
      const double p = face.v_period();
      f[k].y() -= p * std::round((f[k].y() - f[0].y()) / p);
    }
  }
  return box_of(f);
}

template <std::size_t N>
double largest_gap(const std::array<BoundCorner, N>& c, const std::array<Vec3, N>& s) {
  double r = 0;
  for (std::size_t k = 0; k < N; ++k) r = std::max(r, (c[k].x - s[k]).norm());
  return r;
}

bool inside(const UvBounds& a, const UvBounds& b) {
  return a.u_min >= b.u_min && a.u_max <= b.u_max && a.v_min >= b.v_min && a.v_max <= b.v_max;
}

// The bilinear map's interpolation error over the (unwrapped) corner
// parameters f, with m bounding S's second derivatives over their box.
double bilinear_error(const std::array<Vec2, 4>& f, const SecondDerivativeBound& m) {
  // phi_s = (1 - t)(f1 - f0) + t (f2 - f3), phi_t = (1 - s)(f3 - f0) + s (f2 - f1).
  const Vec2 s = (f[1] - f[0]).cwiseAbs().cwiseMax((f[2] - f[3]).cwiseAbs());
  const Vec2 t = (f[3] - f[0]).cwiseAbs().cwiseMax((f[2] - f[1]).cwiseAbs());
  return (along_edge(m, s.x(), s.y()) + along_edge(m, t.x(), t.y())) / 8;
}

// The interpolation error's bound for the corners' parameters f (N = 4:
// bilinear, N = 3: linear); -1 for a surface without bounds.
template <std::size_t N>
double interpolation_error(const SurfaceFace& face, std::array<Vec2, N> f,
                           const CurvatureOverBox* hint = nullptr) {
  const UvBounds box = unwrap(face, f);
  SecondDerivativeBound m;
  if (hint && inside(box, hint->box))
    m = hint->m;
  else if (!face.second_derivative_bound(box, m))
    return -1;
  if constexpr (N == 4) {
    return bilinear_error(f, m);
  } else {
    // e(x) = sum_k l_k R_k, |R_k| <= 1/2 |D^2 S[f_k - phi(x), same]|; the
    // weighted spreads of the f_k's u and v are at most a quarter of their
    // ranges squared (the cross term, by Cauchy-Schwarz, of their product).
    return along_edge(m, box.u_max - box.u_min, box.v_max - box.v_min) / 8;
  }
}

template <std::size_t N>
double cell_bound(const SurfaceFace& face, const std::array<BoundCorner, N>& c, double enough,
                  const CurvatureOverBox* hint) {
  Choice<N> feet, own;
  for (std::size_t k = 0; k < N; ++k) {
    feet.f[k] = c[k].f, feet.s[k] = c[k].s;
    own.f[k] = c[k].q, own.s[k] = c[k].s_q;
  }
  const double gap = largest_gap(c, feet.s);
  if (hint) {
    const double e = interpolation_error(face, feet.f, hint);
    if (e >= 0 && gap + e <= enough) return gap + e;
  }
  const double e_feet = interpolation_error(face, feet.f);
  if (e_feet < 0) return std::numeric_limits<double>::infinity();
  double best = gap + e_feet;
  if (best <= enough) return best;
  best = std::min(best, largest_gap(c, own.s) + interpolation_error(face, own.f));
  if (best <= enough) return best;
  if constexpr (N == 4) {
    // Along a crease that crosses the cell between two opposite edges, the
    // feet of one edge serve the opposite edge too (phi constant across).
    static const int share[4][4] = {{0, 1, 1, 0}, {3, 2, 2, 3}, {0, 0, 3, 3}, {1, 1, 2, 2}};
    for (const auto& from : share) {
      Choice<N> one;
      for (std::size_t k = 0; k < N; ++k) one.f[k] = c[from[k]].f, one.s[k] = c[from[k]].s;
      best = std::min(best, largest_gap(c, one.s) + interpolation_error(face, one.f));
      if (best <= enough) return best;
    }
  }
  for (std::size_t k = 0; k < N; ++k)
    for (const Vec3* s : {&c[k].s, &c[k].s_q}) {
      double r = 0;
      for (const BoundCorner& o : c) r = std::max(r, (o.x - *s).norm());
      best = std::min(best, r);
    }
  return best;
}

}  // namespace

double bilinear_hint_bound(const std::array<Vec2, 4>& feet, double gap,
                           const CurvatureOverBox& hint) {
  if (!inside(box_of(feet), hint.box)) return -1;
  return gap + bilinear_error(feet, hint.m);
}

double along_edge(const SecondDerivativeBound& m, double du, double dv) {
  return m.uu * du * du + 2 * m.uv * du * dv + m.vv * dv * dv;
}

double bilinear_cell_bound(const SurfaceFace& face, const std::array<BoundCorner, 4>& c,
                           double enough, const CurvatureOverBox* hint) {
  return cell_bound(face, c, enough, hint);
}

double triangle_cell_bound(const SurfaceFace& face, const std::array<BoundCorner, 3>& c,
                           double enough, const CurvatureOverBox* hint) {
  return cell_bound(face, c, enough, hint);
}

}  // namespace tessella
