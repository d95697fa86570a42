// Closed-form checks of the cut of general quad cells by the trims
// (mesh/cell_clipping.h) and of relaxed_grid, which tiles a trimmed face with it.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <vector>

#include "mesh/cell_clipping.h"
#include "mesh/panel_model.h"
#include "tessella/relaxed_grid.h"
#include "test_faces.h"

using namespace tessella;
using namespace tessella::test;

namespace {

double polygon_area(const std::vector<Vec2>& p) {
  double a = 0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    const Vec2& s = p[k];
    const Vec2& t = p[(k + 1) % p.size()];
    a += s.x() * t.y() - t.x() * s.y();
  }
  return 0.5 * a;
}

double panel_uv_area(const PanelMesh& m, std::size_t k) {
  std::vector<Vec2> uv;
  for (int v : m.panels[k]) uv.push_back(m.uv[std::size_t(v)]);
  return polygon_area(uv);
}

double total_area(const PanelMesh& m) {
  double a = 0;
  for (std::size_t k = 0; k < m.panels.size(); ++k) a += panel_area(m, k);
  return a;
}

// The index of the vertex at (x, y) (-1 if none).
int vertex_at(const PanelMesh& m, double x, double y) {
  for (std::size_t v = 0; v < m.uv.size(); ++v)
    if ((m.uv[v] - Vec2(x, y)).norm() < 1e-6) return static_cast<int>(v);
  return -1;
}

int panels_using(const PanelMesh& m, int v) {
  int n = 0;
  for (const auto& p : m.panels) n += std::count(p.begin(), p.end(), v) > 0 ? 1 : 0;
  return n;
}

// No T-junction: every side is used by at most two panels (once each way),
// and no vertex lies inside another panel's side without being its corner.
void expect_no_t_junctions(const PanelMesh& m) {
  std::map<std::array<int, 2>, int> uses;
  for (const auto& p : m.panels)
    for (std::size_t k = 0; k < p.size(); ++k) {
      const int a = p[k], b = p[(k + 1) % p.size()];
      const std::array<int, 2> side = {a, b};
      EXPECT_EQ(++uses[side], 1) << a << "->" << b;
    }
  for (const auto& [side, n] : uses) {
    (void)n;
    const Vec2 a = m.uv[std::size_t(side[0])], d = m.uv[std::size_t(side[1])] - a;
    for (std::size_t v = 0; v < m.uv.size(); ++v) {
      const Vec2 q = m.uv[v] - a;
      const double t = q.dot(d) / d.squaredNorm();
      const double off = std::abs(q.x() * d.y() - q.y() * d.x()) / d.norm();
      EXPECT_FALSE(t > 1e-9 && t < 1 - 1e-9 && off < 1e-7)
          << "vertex " << v << " on side " << side[0] << "->" << side[1];
    }
  }
}

// 3 x 3 nodes on the plate [0,1000]^2, border nodes on the border, the middle
// node moved: four general quads. The hole [400,600]^2 lies wholly inside
// cell (1,0) = (200,0), (1000,0), (1000,600), (300,700).
std::vector<Vec2> skewed_nodes() {
  return {{0, 0},    {200, 0},    {1000, 0},    //
          {0, 800},  {300, 700},  {1000, 600},  //
          {0, 1000}, {400, 1000}, {1000, 1000}};
}

}  // namespace

TEST(CellClipping, AnOpeningInsideOneSkewedCellSplitsItAndTheNeighbourGetsTheSplitNode) {
  const SurfaceFace f = plate_with_square_hole(1000, 400, 600);
  const PanelMesh m = clip_cells(f, skewed_nodes(), 3, 3, GridClipParams{});
  // Three whole cells, the fourth split in two by x = 500 through the hole.
  ASSERT_EQ(m.panels.size(), 5u);
  EXPECT_NEAR(total_area(m), 1e6 - 200.0 * 200.0, 1e-6);
  // The split meets the cell's top edge (1000,600)-(300,700) at y(500):
  const double y500 = 600 + 100.0 * (1000 - 500) / 700;
  const double left = polygon_area({{200, 0}, {500, 0}, {500, y500}, {300, 700}}) - 100 * 200;
  const double right = polygon_area({{500, 0}, {1000, 0}, {1000, 600}, {500, y500}}) - 100 * 200;
  std::vector<double> areas;
  for (std::size_t k = 0; k < m.panels.size(); ++k) {
    EXPECT_GT(panel_uv_area(m, k), 0.0);  // counter-clockwise, simple
    areas.push_back(panel_uv_area(m, k));
  }
  EXPECT_EQ(std::count_if(areas.begin(), areas.end(),
                          [&](double a) { return std::abs(a - left) < 1e-6; }),
            1);
  EXPECT_EQ(std::count_if(areas.begin(), areas.end(),
                          [&](double a) { return std::abs(a - right) < 1e-6; }),
            1);
  // The split node on the slanted edge is a corner of both halves and of the
  // cell above (no T-junction there); the split meets the hole at two nodes.
  const int top = vertex_at(m, 500, y500);
  ASSERT_GE(top, 0);
  EXPECT_EQ(panels_using(m, top), 3);
  EXPECT_TRUE(is_node(m, top));
  for (double y : {0.0, 400.0, 600.0}) {
    const int v = vertex_at(m, 500, y);
    ASSERT_GE(v, 0) << y;
    EXPECT_EQ(panels_using(m, v), 2) << y;
    EXPECT_TRUE(is_node(m, v));
  }
  // The hole's corners are nodes of the panels around it.
  for (double x : {400.0, 600.0})
    for (double y : {400.0, 600.0}) {
      const int v = vertex_at(m, x, y);
      ASSERT_GE(v, 0);
      EXPECT_TRUE(is_node(m, v));
    }
  expect_no_t_junctions(m);
}

TEST(CellClipping, CellsCrossingTheTrimFollowItAndShareTheirCrossings) {
  // 5 x 5 cells, interior nodes moved off the tensor grid, the hole [330,670]^2
  // cut by many slanted edges.
  const SurfaceFace f = plate_with_square_hole(1000, 330, 670);
  const int n = 6;
  std::vector<Vec2> nodes;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const bool border_u = i == 0 || i == n - 1, border_v = j == 0 || j == n - 1;
      const double du = border_u ? 0.0 : 37.0 * std::sin(1.3 * i + 2.1 * j);
      const double dv = border_v ? 0.0 : 41.0 * std::cos(0.7 * i - 1.9 * j);
      nodes.push_back({200.0 * i + du, 200.0 * j + dv});
    }
  GridClipParams keep;
  keep.sliver_fraction = 0.0;
  const PanelMesh m = clip_cells(f, nodes, n, n, keep);
  EXPECT_NEAR(total_area(m), 1e6 - 340.0 * 340.0, 1e-6);
  double uv_area = 0;
  for (std::size_t k = 0; k < m.panels.size(); ++k) {
    EXPECT_GT(panel_uv_area(m, k), 0.0);
    uv_area += panel_uv_area(m, k);
  }
  EXPECT_NEAR(uv_area, 1e6 - 340.0 * 340.0, 1e-6);
  expect_no_t_junctions(m);
  // Every vertex lies in the face; those on the hole's border that are not
  // its corners are crossings of a cell edge (nodes, two panels each).
  for (std::size_t v = 0; v < m.uv.size(); ++v) {
    const Vec2 q = m.uv[v];
    EXPECT_FALSE(q.x() > 330 + 1e-9 && q.x() < 670 - 1e-9 && q.y() > 330 + 1e-9 &&
                 q.y() < 670 - 1e-9);
    const bool on_hole = std::max(std::abs(q.x() - 500), std::abs(q.y() - 500)) > 170 - 1e-7 &&
                         std::max(std::abs(q.x() - 500), std::abs(q.y() - 500)) < 170 + 1e-7;
    const bool corner = std::abs(std::abs(q.x() - 500) - 170) < 1e-7 &&
                        std::abs(std::abs(q.y() - 500) - 170) < 1e-7;
    if (on_hole) {
      EXPECT_TRUE(is_node(m, static_cast<int>(v)));
    }
    if (on_hole && !corner) {
      EXPECT_EQ(panels_using(m, static_cast<int>(v)), 2);
    }
  }
  // Deterministic: the same mesh again.
  const PanelMesh again = clip_cells(f, nodes, n, n, keep);
  EXPECT_EQ(again.panels, m.panels);
  EXPECT_EQ(again.uv, m.uv);
}

TEST(CellClipping, RowsAHairOffATrimMeetItNodeToNode) {
  // A 10 x 10 lattice of 100 mm cells and a hole whose sides run 0.03-0.04 mm
  // beside its lines x, y = 300 and 700 (a net laid along the cuts it was
  // split by, each computed to its own tolerance). Without the snap every
  // cell beside the hole kept a 0.04 mm sliver and the rows met the trim in
  // crossings at the slivers' ends.
  const double lo = 300.04, hi = 699.97;
  const SurfaceFace f = plate_with_square_hole(1000, lo, hi);
  const int n = 11;
  std::vector<Vec2> nodes;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) nodes.push_back({100.0 * i, 100.0 * j});
  GridClipParams keep;
  keep.sliver_fraction = 0.0;  // no merge hides a sliver
  const PanelMesh m = clip_cells(f, nodes, n, n, keep);
  // The 16 cells over the hole go; the 84 others stay whole quads.
  ASSERT_EQ(m.panels.size(), 84u);
  for (const auto& p : m.panels) EXPECT_EQ(p.size(), 4u);
  EXPECT_NEAR(total_area(m), 1e6 - (hi - lo) * (hi - lo), 1e-6);
  expect_no_t_junctions(m);
  // Every vertex on the hole's border is a node moved onto it: 16 of them,
  // the hole's four corners among them; every other vertex is a lattice node
  // where it was.
  int on_hole = 0;
  for (std::size_t v = 0; v < m.uv.size(); ++v) {
    const Vec2 q = m.uv[v];
    const double dx = std::min(std::abs(q.x() - lo), std::abs(q.x() - hi));
    const double dy = std::min(std::abs(q.y() - lo), std::abs(q.y() - hi));
    const bool inside_x = q.x() > lo - 1e-9 && q.x() < hi + 1e-9;
    const bool inside_y = q.y() > lo - 1e-9 && q.y() < hi + 1e-9;
    if ((dx < 1e-9 && inside_y) || (dy < 1e-9 && inside_x)) {
      ++on_hole;
      EXPECT_TRUE(is_node(m, static_cast<int>(v)));
      continue;
    }
    const double ri = q.x() / 100.0, rj = q.y() / 100.0;
    EXPECT_NEAR(ri, std::round(ri), 1e-12) << q.transpose();
    EXPECT_NEAR(rj, std::round(rj), 1e-12) << q.transpose();
  }
  EXPECT_EQ(on_hole, 16);
  for (double x : {lo, hi})
    for (double y : {lo, hi}) EXPECT_GE(vertex_at(m, x, y), 0) << x << " " << y;
}

TEST(RelaxedGrid, PlateWithAHoleIsTiledExactlyWithTheOpeningCutOut) {
  // On a plane every rod is straight: the grid stays uniform, 3 x 3 cells of
  // 1000/3 mm; the hole [400,600]^2 lies inside the middle cell, which is
  // split at x = 500 into two C-shaped panels.
  const SurfaceFace f = plate_with_square_hole(1000, 400, 600);
  RelaxedGridParams p;
  p.u_count = p.v_count = 3;
  const PanelMesh m = relaxed_grid(f, p);
  ASSERT_EQ(m.panels.size(), 10u);
  EXPECT_NEAR(total_area(m), 1e6 - 200.0 * 200.0, 1e-6);
  const double half = 1000.0 / 6 * 1000.0 / 3 - 100 * 200;
  int halves = 0, cells = 0;
  for (std::size_t k = 0; k < m.panels.size(); ++k) {
    const double a = panel_uv_area(m, k);
    halves += std::abs(a - half) < 1e-6 ? 1 : 0;
    cells += std::abs(a - 1e6 / 9) < 1e-6 ? 1 : 0;
  }
  EXPECT_EQ(halves, 2);
  EXPECT_EQ(cells, 8);
  // 16 grid nodes, the split's ends on the middle cell's edges, where it
  // meets the hole, and the hole's four corners: all nodes.
  EXPECT_EQ(m.vertex_count(), 16u + 2u + 2u + 4u);
  for (std::size_t v = 0; v < m.vertex_count(); ++v) EXPECT_TRUE(is_node(m, static_cast<int>(v)));
  // The cells above and below the split one carry its end as a fifth node.
  for (double y : {1000.0 / 3, 2000.0 / 3}) {
    const int v = vertex_at(m, 500, y);
    ASSERT_GE(v, 0);
    EXPECT_EQ(panels_using(m, v), 3);
  }
  expect_no_t_junctions(m);
}

TEST(RelaxedGrid, AWholeCellOutsideTheTrimsGoesAndSliversMerge) {
  // Hole [320,680]^2 with 3 x 3 cells: the middle cell [333,667]^2 lies in
  // the hole and goes; its eight neighbours lose a 13 mm strip or corner.
  const SurfaceFace f = plate_with_square_hole(1000, 320, 680);
  RelaxedGridParams p;
  p.u_count = p.v_count = 3;
  const PanelMesh m = relaxed_grid(f, p);
  EXPECT_EQ(m.panels.size(), 8u);
  EXPECT_NEAR(total_area(m), 1e6 - 360.0 * 360.0, 1e-6);
  expect_no_t_junctions(m);
}
