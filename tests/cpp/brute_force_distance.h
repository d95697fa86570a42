// Independent re-measures of a panel model's largest distance to a surface,
// shared by the deviation tests and bench/bench_deviation_truth.cpp: no
// projection of ours is used.
#pragma once

#include <Extrema_GenLocateExtPS.hxx>
#include <GeomAdaptor_Surface.hxx>
#include <Geom_Surface.hxx>
#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "tessella/vec.h"

namespace tessella::test {

// The distance to a surface that is the graph of its parameters (x = u,
// y = v), by brute force: every surface point of a 2 mm, then a 0.5 mm grid
// within reach of x (the nearest point lies within the best distance found
// so far, horizontally too; samples beyond the surface's bounds clamped
// onto its border), then from the four nearest grid points at least 1 mm
// apart OCCT's local extremum search and a compass search clamped to the
// bounds (a nearest point on the border has no orthogonal foot).
class GraphDistance {
 public:
  explicit GraphDistance(const Handle(Geom_Surface) & s)
      : surface_(s), adaptor_(s), locate_(adaptor_) {
    s->Bounds(u0_, u1_, v0_, v1_);
  }

  double operator()(const Vec3& x) {
    const gp_Pnt at(x.x(), x.y(), x.z());
    double best =
        surface_->Value(std::clamp(x.x(), u0_, u1_), std::clamp(x.y(), v0_, v1_)).Distance(at);
    std::vector<std::array<double, 3>> near;  // (d, u, v) of the 0.5 mm pass
    for (const double step : {2.0, 0.5}) {
      const int n = int(std::ceil(best / step));
      for (int i = -n; i <= n; ++i)
        for (int j = -n; j <= n; ++j) {
          double u = x.x() + step * i, v = x.y() + step * j;
          // Within reach, clamped to the surface (beyond its bounds OCCT
          // would extrapolate its end spans; clamped, the border is sampled).
          if (std::hypot(u - x.x(), v - x.y()) > best) continue;
          u = std::clamp(u, u0_, u1_), v = std::clamp(v, v0_, v1_);
          const double d = surface_->Value(u, v).Distance(at);
          if (step < 1) near.push_back({d, u, v});
          best = std::min(best, d);
        }
    }
    std::sort(near.begin(), near.end());
    std::vector<std::array<double, 3>> starts;
    for (const auto& c : near) {
      bool apart = true;
      for (const auto& s : starts) apart = apart && std::hypot(c[1] - s[1], c[2] - s[2]) >= 1.0;
      if (apart) starts.push_back(c);
      if (starts.size() == 4) break;
    }
    for (const auto& s : starts) {
      locate_.Perform(at, s[1], s[2], Standard_False);
      double u, v;
      if (locate_.IsDone()) {
        locate_.Point().Parameter(u, v);
        if (u >= u0_ && u <= u1_ && v >= v0_ && v <= v1_)
          best = std::min(best, std::sqrt(locate_.SquareDistance()));
      }
      // And a compass search clamped to the bounds: the nearest point may lie
      // on the border, where no orthogonal foot exists.
      u = s[1], v = s[2];
      double d = s[0];
      for (double h = 0.5; h > 1e-7;) {
        bool moved = false;
        for (auto [du, dv] :
             {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1}, {-1, -1}, {1, -1}, {-1, 1}}) {
          const double nu = std::clamp(u + h * du, u0_, u1_), nv = std::clamp(v + h * dv, v0_, v1_);
          const double nd = surface_->Value(nu, nv).Distance(at);
          if (nd < d) {
            d = nd, u = nu, v = nv, moved = true;
            break;
          }
        }
        if (!moved) h *= 0.5;
      }
      best = std::min(best, d);
    }
    return best;
  }

 private:
  Handle(Geom_Surface) surface_;
  GeomAdaptor_Surface adaptor_;
  Extrema_GenLocateExtPS locate_;
  double u0_ = 0, u1_ = 0, v0_ = 0, v1_ = 0;
};

// The largest distance of a quad's bilinear model p (4 points): an
// (n + 1) x (n + 1) grid, then a compass search from its three largest
// points down to a step of 1e-4. A lower bound of the true maximum where
// `distance` is exact.
template <class Distance, class Points>
double dense_quad_maximum(Distance& distance, const Points& p, int n = 16) {
  auto dist = [&](double s, double t) {
    return distance((1 - s) * (1 - t) * p[0] + s * (1 - t) * p[1] + s * t * p[2] +
                    (1 - s) * t * p[3]);
  };
  std::vector<std::array<double, 3>> grid;
  for (int a = 0; a <= n; ++a)
    for (int b = 0; b <= n; ++b)
      grid.push_back({dist(double(a) / n, double(b) / n), double(a) / n, double(b) / n});
  std::sort(grid.begin(), grid.end(), [](const auto& x, const auto& y) { return x[0] > y[0]; });
  double worst = 0;
  for (int k = 0; k < 3; ++k) {
    auto [d, s, t] = grid[k];
    for (double h = 0.5 / n; h > 1e-4;) {
      bool moved = false;
      for (auto [ds, dt] :
           {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1}, {-1, -1}, {1, -1}, {-1, 1}}) {
        const double ns = s + h * ds, nt = t + h * dt;
        if (ns < 0 || ns > 1 || nt < 0 || nt > 1) continue;
        const double nd = dist(ns, nt);
        if (nd > d) {
          d = nd, s = ns, t = nt, moved = true;
          break;
        }
      }
      if (!moved) h *= 0.5;
    }
    worst = std::max(worst, d);
  }
  return worst;
}

}  // namespace tessella::test
