// KnownSurfacePoints answers exactly as the linear scan it replaces: the same
// index and distance for every query, also for points outside its box, for
// ties within `tiny`, for an infinite start and for a flat (degenerate) box.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "analysis/known_surface_points.h"

using namespace tessella;

namespace {

std::size_t linear_nearer(const std::vector<Vec3>& pts, const Vec3& x, double& d_near, double tiny,
                          std::size_t from = 0) {
  std::size_t near = pts.size();
  for (std::size_t k = from; k < pts.size(); ++k) {
    const double d = (pts[k] - x).norm();
    if (d + tiny < d_near) d_near = d, near = k;
  }
  return near;
}

void check_against_scan(const Vec3& box_lo, const Vec3& box_hi, double spread, double tiny,
                        unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-spread, 1 + spread);
  KnownSurfacePoints known;
  known.reset(box_lo, box_hi);
  std::vector<Vec3> pts;
  auto random_point = [&] {
    const Vec3 t(u(rng), u(rng), u(rng));
    return Vec3(box_lo + t.cwiseProduct(box_hi - box_lo));
  };
  int taken = 0;
  for (int step = 0; step < 600; ++step) {
    const Vec3 p = random_point();
    // Every third point repeats an earlier one (ties decided by order).
    const Vec3 q = step % 3 == 2 && !pts.empty() ? pts[pts.size() / 2] : p;
    known.add(Vec2(step, -step), q);
    pts.push_back(q);
    const Vec3 x = random_point();
    for (double start : {0.01, 0.1, 0.5, 3.0, std::numeric_limits<double>::infinity()}) {
      const double scale = (box_hi - box_lo).norm();
      double a = start * scale, b = start * scale;
      if (std::isinf(start)) a = b = start;
      const std::size_t got = known.nearer(x, a, tiny);
      const std::size_t want = linear_nearer(pts, x, b, tiny);
      ASSERT_EQ(got, want) << "step " << step << " start " << start;
      ASSERT_EQ(a, b);
      if (got < pts.size()) {
        ++taken;
        EXPECT_EQ(known.uv(got), Vec2(double(got), -double(got)));
        EXPECT_EQ(known.xyz(got), pts[got]);
      }
      // Only the points from `from` on (a recheck of an earlier probe).
      for (std::size_t from : {std::size_t(0), pts.size() / 3, pts.size() - 1, pts.size()}) {
        double c = a, d = a;
        ASSERT_EQ(known.nearer(x, c, tiny, from), linear_nearer(pts, x, d, tiny, from))
            << "step " << step << " from " << from;
        ASSERT_EQ(c, d);
      }
    }
  }
  EXPECT_GT(taken, 100);  // the queries did find nearer points
}

}  // namespace

TEST(KnownSurfacePoints, SameAnswerAsTheLinearScan) {
  check_against_scan(Vec3(0, 0, 0), Vec3(1000, 800, 50), 0.0, 1e-6, 1);
}

TEST(KnownSurfacePoints, PointsOutsideTheBoxAreFound) {
  check_against_scan(Vec3(-5, 10, 0), Vec3(5, 30, 2), 0.8, 1e-9, 2);
}

TEST(KnownSurfacePoints, TiesWithinTinyAndAFlatBox) {
  // A box flat in z (a planar panel) and a coarse tiny: many near-ties.
  check_against_scan(Vec3(0, 0, 7), Vec3(100, 100, 7), 0.3, 0.5, 3);
}

TEST(KnownSurfacePoints, EmptyOrDegenerate) {
  KnownSurfacePoints known;
  known.reset(Vec3::Zero(), Vec3::Zero());  // a single point as box
  double d = 1.0;
  EXPECT_EQ(known.nearer(Vec3(1, 2, 3), d, 1e-9), 0u);  // none: size() == 0
  known.add(Vec2(0.5, 0.5), Vec3(1, 2, 3.5));
  d = 1.0;
  EXPECT_EQ(known.nearer(Vec3(1, 2, 3), d, 1e-9), 0u);
  EXPECT_DOUBLE_EQ(d, 0.5);
  d = std::nan("");
  EXPECT_EQ(known.nearer(Vec3(1, 2, 3), d, 1e-9), 1u);  // NaN: nothing is nearer
}

TEST(KnownSurfacePoints, ASheetOfPointsUnderProbesAboveIt) {
  // The measure's case: the points lie on a wavy sheet (the surface under a
  // panel) and each query stands above it, its start its height: the cells
  // under the query's box hold many points, but its ball only touches the
  // sheet (cells whose points' box is outside the ball are skipped). Also
  // after a reset to a smaller grid, whose cells reuse the earlier boxes'
  // storage.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  KnownSurfacePoints known;
  for (double side : {2000.0, 300.0}) {
    known.reset(Vec3(0, 0, -40), Vec3(side, side, 40));
    std::vector<Vec3> pts;
    auto sheet = [side](double a, double b) {
      return Vec3(a * side, b * side, 30.0 * std::sin(7 * a) * std::cos(5 * b));
    };
    int taken = 0;
    for (int step = 0; step < 1500; ++step) {
      const Vec3 p = sheet(u(rng), u(rng));
      known.add(Vec2(step, 0), p);
      pts.push_back(p);
      const double a = u(rng), b = u(rng), h = 0.2 * side * u(rng);
      const Vec3 x = sheet(a, b) + Vec3(0, 0, h);
      double got_d = h, want_d = h;
      const std::size_t got = known.nearer(x, got_d, 1e-9);
      ASSERT_EQ(got, linear_nearer(pts, x, want_d, 1e-9)) << "side " << side << " step " << step;
      ASSERT_EQ(got_d, want_d);
      taken += got < pts.size();
    }
    EXPECT_GT(taken, 100);
  }
}
