// The short-rod stage (mesh/short_rod_merge.h) on synthetic grids cut by a
// plate's trims: grid lines 1 mm from a trim corner and from a hole's edge.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "mesh/grid_clipping.h"
#include "mesh/panel_model.h"
#include "mesh/short_rod_merge.h"
#include "tessella/errors.h"
#include "test_faces.h"

namespace tessella {
namespace {

SurfaceFace plate(double size) {
  return SurfaceFace::from_brep_string(
      test::brep(BRepBuilderAPI_MakeFace(gp_Pln(), test::rect_wire(0, 0, size, size, false)).Face()));
}

double shortest_rod(const PanelMesh& m) {
  double best = 1e300;
  for (const auto& r : m.rods) best = std::min(best, (m.xyz[r[0]] - m.xyz[r[1]]).norm());
  return best;
}

double total_area(const PanelMesh& m) {
  double a = 0;
  for (std::size_t p = 0; p < m.panels.size(); ++p) a += panel_area(m, p);
  return a;
}

// Vertices on an edge only one panel uses.
std::set<int> boundary_vertices(const PanelMesh& m) {
  std::set<std::pair<int, int>> edges;
  for (const auto& p : m.panels)
    for (std::size_t k = 0; k < p.size(); ++k) edges.insert({p[k], p[(k + 1) % p.size()]});
  std::set<int> out;
  for (const auto& [a, b] : edges)
    if (!edges.count({b, a})) out.insert(a), out.insert(b);
  return out;
}

bool on_square(const Vec3& x, double x0, double x1) {
  const auto at = [](double a, double b) { return std::abs(a - b) <= 1e-9; };
  const bool in = x.x() >= x0 - 1e-9 && x.x() <= x1 + 1e-9 && x.y() >= x0 - 1e-9 &&
                  x.y() <= x1 + 1e-9;
  return in && (at(x.x(), x0) || at(x.x(), x1) || at(x.y(), x0) || at(x.y(), x1));
}

void check_panels(const PanelMesh& m) {
  for (const auto& p : m.panels) {
    ASSERT_GE(p.size(), 3u);
    int nodes = 0;
    for (int v : p) nodes += is_node(m, v) ? 1 : 0;
    EXPECT_GE(nodes, 3);
  }
}

TEST(ShortRodMerge, CrossingOneMillimetreFromATrimCornerMerges) {
  // Plate [0,1000]^2; the grid line x = 1 crosses the trim 1 mm from the
  // corners (0,0) and (0,1000) and passes 1 mm from the trim at (0,500).
  const SurfaceFace face = plate(1000);
  GridClipParams clip;
  clip.sliver_fraction = 0.0;
  PanelMesh m = clip_grid(face, {0, 1, 500, 1000}, {0, 500, 1000}, clip);
  ASSERT_LT(shortest_rod(m), 1.0 + 1e-9);
  const double area = total_area(m);
  ShortRodMergeParams p;
  p.min_rod_length = 100.0;
  const ShortRodMergeReport rep = merge_short_rods(face, m, p);
  EXPECT_GT(rep.merged, 0);
  EXPECT_EQ(rep.remaining, 0);
  EXPECT_GE(shortest_rod(m), 100.0);
  EXPECT_NEAR(total_area(m), area, 1e-6 * area);
  EXPECT_NEAR(total_area(m), 1e6, 1e-6);
  check_panels(m);
  // Every boundary vertex is exactly on the square; its corners are still nodes.
  std::set<std::pair<double, double>> corners;
  for (int v : boundary_vertices(m)) {
    EXPECT_TRUE(on_square(m.xyz[v], 0, 1000)) << m.xyz[v].transpose();
    if (is_node(m, v)) corners.insert({m.xyz[v].x(), m.xyz[v].y()});
  }
  for (auto c : {std::make_pair(0.0, 0.0), std::make_pair(1000.0, 0.0),
                 std::make_pair(1000.0, 1000.0), std::make_pair(0.0, 1000.0)})
    EXPECT_TRUE(corners.count(c)) << c.first << " " << c.second;
}

TEST(ShortRodMerge, GridNodesNextToAHoleMoveOntoItsEdge) {
  // Hole [300,700]^2; the line x = 299 runs 1 mm beside its left edge.
  const SurfaceFace face = test::plate_with_square_hole(1000, 300, 700);
  GridClipParams clip;
  clip.sliver_fraction = 0.0;
  PanelMesh m = clip_grid(face, {0, 299, 500, 1000}, {0, 250, 500, 750, 1000}, clip);
  ASSERT_LT(shortest_rod(m), 1.0 + 1e-9);
  const double area = total_area(m);
  EXPECT_NEAR(automatic_min_rod_length(m), 0.25 * std::sqrt(m.nominal_area), 1e-9);
  ShortRodMergeParams p;
  p.min_rod_length = 20.0;
  const ShortRodMergeReport rep = merge_short_rods(face, m, p);
  EXPECT_GT(rep.merged, 0);
  EXPECT_EQ(rep.remaining, 0);
  EXPECT_GE(shortest_rod(m), rep.min_rod_length);
  EXPECT_NEAR(total_area(m), area, 1e-6 * area);
  EXPECT_NEAR(total_area(m), 1e6 - 400.0 * 400.0, 1e-6);
  check_panels(m);
  for (int v : boundary_vertices(m))
    EXPECT_TRUE(on_square(m.xyz[v], 0, 1000) || on_square(m.xyz[v], 300, 700))
        << m.xyz[v].transpose();
}

TEST(ShortRodMerge, NothingShortNothingChanges) {
  const SurfaceFace face = plate(1000);
  PanelMesh m = clip_grid(face, {0, 500, 1000}, {0, 500, 1000}, GridClipParams{});
  const PanelMesh before = m;
  const ShortRodMergeReport rep = merge_short_rods(face, m, ShortRodMergeParams{});
  EXPECT_EQ(rep.merged, 0);
  EXPECT_EQ(m.panels, before.panels);
  EXPECT_EQ(m.rods, before.rods);
}

TEST(ShortRodMerge, NegativeLimitIsRefused) {
  const SurfaceFace face = plate(1000);
  PanelMesh m = clip_grid(face, {0, 500, 1000}, {0, 500, 1000}, GridClipParams{});
  ShortRodMergeParams p;
  p.min_rod_length = -1;
  EXPECT_THROW(merge_short_rods(face, m, p), InvalidParameter);
}

}  // namespace
}  // namespace tessella
