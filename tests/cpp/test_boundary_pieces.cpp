// The boundary-piece stage's choice of bend lines (mesh/boundary_pieces.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <set>

#include "mesh/boundary_pieces.h"
#include "test_faces.h"

using namespace tessella;
using namespace tessella::test;

namespace {

constexpr double kR = 6000.0;
constexpr double kPi = 3.14159265358979323846;

// Largest distance of flat triangle abc from the sphere of radius kR round
// the origin, densely sampled (exact distance: | |x| - R |).
double triangle_deviation(const Vec3& a, const Vec3& b, const Vec3& c) {
  double worst = 0;
  const int n = 40;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; i + j <= n; ++j) {
      const double s = double(i) / n, t = double(j) / n;
      const Vec3 x = (1 - s - t) * a + s * b + t * c;
      worst = std::max(worst, std::abs(x.norm() - kR));
    }
  return worst;
}

// The fan of a pentagon from corner i: its triangles.
std::array<std::array<int, 3>, 3> fan(int i) {
  return {{{i, (i + 1) % 5, (i + 2) % 5},
           {i, (i + 2) % 5, (i + 3) % 5},
           {i, (i + 3) % 5, (i + 4) % 5}}};
}

double fan_deviation(const std::vector<Vec3>& x, int i) {
  double worst = 0;
  for (const auto& t : fan(i))
    worst = std::max(worst, triangle_deviation(x[t[0]], x[t[1]], x[t[2]]));
  return worst;
}

double fan_fold(const std::vector<Vec3>& x, int i) {
  const auto tris = fan(i);
  double worst = 0;
  for (int k = 0; k + 1 < 3; ++k) {
    const auto& a = tris[k];
    const auto& b = tris[k + 1];
    const Vec3 n1 = (x[a[1]] - x[a[0]]).cross(x[a[2]] - x[a[0]]).normalized();
    const Vec3 n2 = (x[b[1]] - x[b[0]]).cross(x[b[2]] - x[b[0]]).normalized();
    worst = std::max(worst, std::acos(std::clamp(n1.dot(n2), -1.0, 1.0)));
  }
  return worst;
}

// Which fan the bend lines (corner pairs) of a pentagon are: the corner all
// of them leave from.
int fan_of(const std::vector<std::array<int, 2>>& bends) {
  for (int i = 0; i < 5; ++i) {
    bool all = bends.size() == 2;
    for (const auto& b : bends) all = all && (b[0] == i || b[1] == i);
    if (all) return i;
  }
  return -1;
}

}  // namespace

// A pentagon of five nodes has no trim point the stage could make a node:
// under a hard bound it must be bent along a triangulation that holds the
// bound when one does, even if another folds less (a pentagon at the British
// Museum roof's corner, bent the least-fold way, measured 128 mm against
// 100 and made walking_agent walk the whole roof again at 76 mm).
TEST(BoundaryPieces, APentagonOfNodesIsBentWithinAHardBoundWhenATriangulationHoldsIt) {
  const SurfaceFace face = sphere_face(kR);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> jitter(-1.0, 1.0);
  int found = 0;
  for (int trial = 0; trial < 400 && found < 3; ++trial) {
    // A convex pentagon in (u,v) round (1.0, 0.3), stretched and jittered.
    std::vector<Vec2> uv;
    const double stretch = 1.0 + 0.8 * std::abs(jitter(random));
    for (int k = 0; k < 5; ++k) {
      const double a = 2 * kPi * (k + 0.25 * jitter(random)) / 5;
      const double r = 0.12 * (1 + 0.3 * jitter(random));
      uv.emplace_back(1.0 + stretch * r * std::cos(a), 0.3 + r * std::sin(a));
    }
    std::vector<Vec3> x;
    for (const Vec2& q : uv) x.push_back(face.point(q.x(), q.y()));
    // The fan that folds least, and the least deviation of any fan.
    int least_fold = 0;
    double best_other = 1e300;
    for (int i = 1; i < 5; ++i)
      if (fan_fold(x, i) < fan_fold(x, least_fold)) least_fold = i;
    for (int i = 0; i < 5; ++i)
      if (i != least_fold) best_other = std::min(best_other, fan_deviation(x, i));
    const double least_fold_deviation = fan_deviation(x, least_fold);
    if (!(best_other < 0.8 * least_fold_deviation)) continue;  // no such pentagon
    const double bound = 0.5 * (best_other + least_fold_deviation);
    ++found;
    for (bool hard : {false, true}) {
      PanelMesh mesh;
      mesh.uv = uv;
      mesh.xyz = x;
      mesh.panels = {{0, 1, 2, 3, 4}};
      mesh.is_node.assign(5, 1);
      BoundaryPiecesParams params;
      params.max_deviation = bound;
      params.hard_bound = hard;
      model_boundary_pieces(face, mesh, params);
      ASSERT_EQ(mesh.panels.size(), 1u);
      ASSERT_EQ(mesh.bends.size(), 1u);
      const int chosen = fan_of(mesh.bends[0]);
      ASSERT_GE(chosen, 0);
      if (hard) {
        EXPECT_LE(fan_deviation(x, chosen), bound) << "trial " << trial;
      } else {
        EXPECT_EQ(chosen, least_fold) << "trial " << trial;  // as before: the least fold
        EXPECT_GT(fan_deviation(x, chosen), bound);
      }
    }
  }
  EXPECT_EQ(found, 3);  // the search found pentagons to test
}

// A panel of more nodes than it can be bent along is split by a new rod
// between two nodes; where several nodes lie in a row along one straight
// side (a shared edge the join filled with the other face's nodes), the
// most even split ran along that side and cut off a part of no area: a
// piece through three nodes in a line, its plane tilted any way (12.6 mm
// against walking_agent's 12 on the roof split along its diagonals).
TEST(BoundaryPieces, ASplitNeverCutsOffASliverAlongARowOfNodes) {
  const SurfaceFace face = sphere_face(kR);
  // Six nodes along the bottom side (bowed out by 1e-7: the chords between
  // them run just inside), then two corners high above.
  std::vector<Vec2> uv;
  for (int k = 0; k <= 5; ++k) {
    const double s = k / 5.0;
    uv.emplace_back(0.9 + 0.2 * s, 0.15 - 1e-7 * std::sin(kPi * s));
  }
  uv.emplace_back(1.1, 0.45);
  uv.emplace_back(0.9, 0.45);
  auto area = [](const std::vector<Vec2>& q) {
    double twice = 0;
    for (std::size_t i = 0; i < q.size(); ++i) {
      const Vec2& a = q[i];
      const Vec2& b = q[(i + 1) % q.size()];
      twice += a.x() * b.y() - a.y() * b.x();
    }
    return 0.5 * std::abs(twice);
  };
  const double whole = area(uv);
  PanelMesh mesh;
  mesh.uv = uv;
  for (const Vec2& q : uv) mesh.xyz.push_back(face.point(q.x(), q.y()));
  mesh.panels = {{0, 1, 2, 3, 4, 5, 6, 7}};
  mesh.is_node.assign(uv.size(), 1);
  BoundaryPiecesParams params;
  const BoundaryPiecesReport report = model_boundary_pieces(face, mesh, params);
  EXPECT_GE(report.split, 1);
  ASSERT_GE(mesh.panels.size(), 2u);
  double total = 0;
  for (const auto& panel : mesh.panels) {
    std::vector<Vec2> q;
    for (int v : panel) q.push_back(mesh.uv[static_cast<std::size_t>(v)]);
    EXPECT_GT(area(q), 0.05 * whole) << "a sliver of " << panel.size() << " corners";
    total += area(q);
  }
  EXPECT_NEAR(total, whole, 1e-9 * whole);
}
