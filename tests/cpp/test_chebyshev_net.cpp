// The Chebyshev net (tessella/chebyshev_net.h) against closed forms: on a
// plane it is the square grid of side `size` whatever the parameterization,
// on a cylinder (developable) the grid of equal angle and height steps; on a
// sphere every rod of the net is `size` long and the panels tile the face.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <vector>

#include "methods/grids/path_along_cuts.h"
#include "tessella/chebyshev_net.h"
#include "tessella/errors.h"
#include "test_faces.h"

using namespace tessella;
using namespace tessella::test;

namespace {

// The lattice index (i, j) of the seed: the node at the seed's (u,v).
std::pair<int, int> seed_index(const ChebyshevLattice& l, const Vec2& seed) {
  for (int j = 0; j < l.nv; ++j)
    for (int i = 0; i < l.nu; ++i)
      if ((l.uv[std::size_t(j) * l.nu + i] - seed).norm() == 0) return {i, j};
  ADD_FAILURE() << "no node at the seed";
  return {0, 0};
}

// Calls fn(k, di, dj) for every node k of the net, (di, dj) its lattice
// offset from the seed; returns their count.
template <class Fn>
int for_each_net_node(const ChebyshevLattice& l, const Vec2& seed, Fn fn) {
  const auto [si, sj] = seed_index(l, seed);
  int count = 0;
  for (int j = 0; j < l.nv; ++j)
    for (int i = 0; i < l.nu; ++i) {
      const std::size_t k = std::size_t(j) * l.nu + i;
      if (!l.on_net[k]) continue;
      ++count;
      fn(k, i - si, j - sj);
    }
  return count;
}

Vec2 seed_of(const SurfaceFace& f, const ChebyshevNetParams& p) {
  const UvBounds b = f.bounds();
  return {b.u_min + p.seed_u * (b.u_max - b.u_min), b.v_min + p.seed_v * (b.v_max - b.v_min)};
}

// The panels' total area in (u,v), each by its corners as it sees them
// (across a seam a vertex has one (u,v) per side).
double uv_area(const PanelMesh& m) {
  double a = 0;
  for (std::size_t p = 0; p < m.panels.size(); ++p) {
    const std::vector<Vec2>& c = m.corner_uv[p];
    for (std::size_t k = 0; k < c.size(); ++k) {
      const Vec2 &s = c[k], &t = c[(k + 1) % c.size()];
      a += 0.5 * (s.x() * t.y() - t.x() * s.y());
    }
  }
  return a;
}

}  // namespace

TEST(ChebyshevNet, OnAStretchedPlaneItIsTheSquareGridOfItsSize) {
  const SurfaceFace f = stretched_plate();  // x = 400u + 600u^2, y = 1000 v
  ChebyshevNetParams p;
  p.size = 70.0;
  p.seed_u = 0.3, p.seed_v = 0.6;
  const ChebyshevLattice l = chebyshev_lattice(f, p);
  const Vec2 seed = seed_of(f, p);
  const Vec3 s = f.point(seed.x(), seed.y());
  const int on_net = for_each_net_node(l, seed, [&](std::size_t k, int di, int dj) {
    const Vec3 expected = s + Vec3(di * p.size, dj * p.size, 0);
    EXPECT_LT((f.point(l.uv[k].x(), l.uv[k].y()) - expected).norm(), 1e-9 * p.size)
        << "node " << di << ", " << dj;
  });
  // Nodes 70 mm apart from the seed (x = 400 0.3 + 600 0.09 = 174, y = 600)
  // within the square [0,1000]^2: x from 34 to 944, y from 40 to 950.
  EXPECT_EQ(on_net, 14 * 14);
  const PanelMesh m = chebyshev_net(f, p);
  EXPECT_NEAR(uv_area(m), 1.0, 1e-9);  // the panels tile the unit (u,v) square
}

TEST(ChebyshevNet, OnACylinderItStepsEqualAnglesAndHeights) {
  const double r = 500, h = 800;
  const SurfaceFace f = cylinder_face(r, h);  // u: angle, v: height
  ChebyshevNetParams p;
  p.size = 90.0;
  const ChebyshevLattice l = chebyshev_lattice(f, p);
  const Vec2 seed = seed_of(f, p);
  const double angle = 2 * std::asin(p.size / (2 * r));
  const int on_net = for_each_net_node(l, seed, [&](std::size_t k, int di, int dj) {
    EXPECT_NEAR(l.uv[k].x(), seed.x() + di * angle, 1e-9);
    EXPECT_NEAR(l.uv[k].y(), seed.y() + dj * p.size, 1e-9 * h);
  });
  // Round the seam: every node of angle within the period, height within 800.
  const int around = 2 * int(std::floor(M_PI / angle)) + 1, up = 2 * int(400 / 90.0) + 1;
  EXPECT_EQ(on_net, around * up);
  const PanelMesh m = chebyshev_net(f, p);
  EXPECT_NEAR(uv_area(m), 2 * M_PI * h, 1e-9 * 2 * M_PI * h);
}

TEST(ChebyshevNet, OnASphereEveryRodOfTheNetHasItsLengthAndThePanelsTileTheFace) {
  // A zone from 50 deg south to 60 deg north, 200 deg round (no seam, no
  // pole, where a welded corner would leave the (u,v) area).
  BRepPrimAPI_MakeSphere zone(1000, -50 * M_PI / 180, 60 * M_PI / 180, 200 * M_PI / 180);
  const SurfaceFace f = SurfaceFace::from_brep_string(brep(first_face(zone.Shape())));
  ChebyshevNetParams p;
  p.size = 150.0;
  ChebyshevNetReport report;
  const PanelMesh m = chebyshev_net(f, p, &report);
  const ChebyshevLattice l = chebyshev_lattice(f, p);
  int rods = 0;
  for (int j = 0; j < l.nv; ++j)
    for (int i = 0; i < l.nu; ++i) {
      const std::size_t k = std::size_t(j) * l.nu + i;
      const Vec3 a = f.point(l.uv[k].x(), l.uv[k].y());
      for (const std::size_t n : {k + 1, k + std::size_t(l.nu)}) {
        if ((n == k + 1 && i + 1 >= l.nu) || (n != k + 1 && j + 1 >= l.nv)) continue;
        if (!l.on_net[k] || !l.on_net[n]) continue;
        const Vec3 b = f.point(l.uv[n].x(), l.uv[n].y());
        EXPECT_NEAR((b - a).norm(), p.size, 1e-9 * p.size);
        ++rods;
      }
    }
  // The net reaches over the whole zone (about 253 cells of 150 mm) but a
  // few nodes by its rim, whose place at 150 mm lies past the surface's end.
  EXPECT_LT(report.extrapolated_nodes, report.net_nodes / 20);
  EXPECT_GT(report.net_nodes, 250);
  EXPECT_GT(rods, 450);
  const UvBounds b = f.bounds();
  const double area = (b.u_max - b.u_min) * (b.v_max - b.v_min);
  EXPECT_NEAR(uv_area(m), area, 1e-9 * area);
}

// No net covers a whole sphere (its total curvature is over 2 pi): beyond
// the net's shear limit the guesses fold, and are laid out again until no
// cell over the face turns over.
TEST(ChebyshevNet, OnAWholeSphereNoCellTurnsOver) {
  const SurfaceFace f = sphere_face(1000);
  ChebyshevNetParams p;
  p.size = 150.0;
  const ChebyshevLattice l = chebyshev_lattice(f, p);
  const UvBounds b = f.bounds();
  int over = 0;
  for (int j = 0; j + 1 < l.nv; ++j)
    for (int i = 0; i + 1 < l.nu; ++i) {
      const Vec2 q[4] = {l.uv[std::size_t(j) * l.nu + i], l.uv[std::size_t(j) * l.nu + i + 1],
                         l.uv[std::size_t(j + 1) * l.nu + i + 1],
                         l.uv[std::size_t(j + 1) * l.nu + i]};
      bool meets = false;
      for (const Vec2& c : q)
        meets |= c.x() > b.u_min && c.x() < b.u_max && c.y() > b.v_min && c.y() < b.v_max;
      if (!meets) continue;
      ++over;
      for (int k = 0; k < 4; ++k) {
        const Vec2 e0 = q[(k + 1) % 4] - q[k], e1 = q[(k + 2) % 4] - q[(k + 1) % 4];
        EXPECT_GT(e0.x() * e1.y() - e0.y() * e1.x(), 0) << "cell " << i << ", " << j;
      }
    }
  EXPECT_GT(over, 500);
  int on_net = 0;
  for (char c : l.on_net) on_net += c;
  EXPECT_GT(on_net, 100);  // the net's middle stays
  EXPECT_GT(chebyshev_net(f, p).panels.size(), 500u);
}

TEST(ChebyshevNet, RefusesBadParameters) {
  const SurfaceFace f = stretched_plate();
  ChebyshevNetParams p;
  EXPECT_THROW(chebyshev_net(f, p), InvalidParameter);  // no size
  p.size = -5;
  EXPECT_THROW(chebyshev_net(f, p), InvalidParameter);
  p.size = 50, p.seed_u = 1.5;
  EXPECT_THROW(chebyshev_net(f, p), InvalidParameter);
  p.seed_u = 0.5, p.size = 0.01;  // 10^10 panels
  EXPECT_THROW(chebyshev_net(f, p), LimitExceeded);
  p.size = 50, p.clip.max_panels = 100;  // 400 panels
  EXPECT_THROW(chebyshev_net(f, p), LimitExceeded);
}

TEST(PathAlongCuts, APathBesideACutFollowsItAndStaysElsewhere) {
  // A plane ((u,v) = (x,y) mm); the cut is the hole [400,600]^2's outline.
  // Paths: along y = 400.6 (0.6 mm beside the cut's side, under 0.01 of the
  // 100 mm rod), along y = 410 (10 mm off: beyond the reach), and across
  // the side at x = 500 (crossing it: stays).
  const SurfaceFace plate = plate_with_square_hole(1000, 400, 600);
  const double size = 100.0;
  const std::vector<std::vector<Vec2>> cuts = {{{400, 400}, {600, 400}, {600, 600}, {400, 600}}};
  const std::vector<Vec2> beside = path_along_cuts(plate, {{0, 400.6}, {1000, 400.6}}, cuts, size);
  ASSERT_GE(beside.size(), 161u);  // resampled: steps of at most size / 16
  int on_cut = 0;
  for (std::size_t k = 0; k < beside.size(); ++k) {
    const Vec2& p = beside[k];
    if (k > 0) {
      EXPECT_LE((p - beside[k - 1]).norm(), size / 16 + 0.01 * size);  // a step and a move
    }
    if (p.x() > 401 && p.x() < 599) {
      EXPECT_NEAR(p.y(), 400.0, 1e-9) << p.transpose();
      ++on_cut;
    } else if (p.x() < 399 || p.x() > 601) {
      EXPECT_EQ(p.y(), 400.6) << p.transpose();  // on the path as given
    }
  }
  EXPECT_GT(on_cut, 25);
  for (const Vec2& p : path_along_cuts(plate, {{0, 410}, {1000, 410}}, cuts, size)) {
    EXPECT_EQ(p.y(), 410.0);
  }
  for (const Vec2& p : path_along_cuts(plate, {{500, 0}, {500, 1000}}, cuts, size)) {
    EXPECT_EQ(p.x(), 500.0);
  }
  // No cuts (one face): the path as given.
  const std::vector<Vec2> path = {{0, 400.6}, {1000, 400.6}};
  EXPECT_EQ(path_along_cuts(plate, path, {}, size), path);
}
