// The coverage measure (analysis/coverage.h) and the zero-area stage
// (mesh/sliver_merge.h) on hand-built meshes of a plane plate, where every
// gap, overlap and spill has a closed-form area (on gp_Pln, (u,v) = (x,y)).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "analysis/coverage.h"
#include "mesh/panel_model.h"
#include "mesh/sliver_merge.h"
#include "tessella/errors.h"
#include "test_faces.h"

namespace tessella {
namespace {

constexpr double kSize = 1000.0;

SurfaceFace plate() {
  return SurfaceFace::from_brep_string(test::brep(
      BRepBuilderAPI_MakeFace(gp_Pln(), test::rect_wire(0, 0, kSize, kSize, false)).Face()));
}

// n x n square panels over [0, kSize]^2, counter-clockwise.
PanelMesh grid(int n) {
  PanelMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const Vec2 q(kSize * i / n, kSize * j / n);
      m.uv.push_back(q);
      m.xyz.push_back(Vec3(q.x(), q.y(), 0));
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i;
      m.panels.push_back({a, a + 1, a + n + 2, a + n + 1});
    }
  build_rods(m);
  m.nominal_area = (kSize / n) * (kSize / n);
  return m;
}

std::vector<double> areas(const PanelMesh& m) {
  std::vector<double> out;
  for (std::size_t p = 0; p < m.panels.size(); ++p) out.push_back(panel_area(m, p));
  return out;
}

TEST(Coverage, ATilingHasNoGapNoOverlap) {
  const SurfaceFace f = plate();
  const PanelMesh m = grid(7);  // lines not on the scanlines' grid
  const Coverage c = measure_coverage(f, m, areas(m));
  EXPECT_NEAR(c.face_area, kSize * kSize, 1e-6 * kSize * kSize);
  EXPECT_LT(c.gap, 1e-9 * c.face_area);
  EXPECT_LT(c.overlap, 1e-9 * c.face_area);
  EXPECT_LT(c.outside, 1e-9 * c.face_area);
  EXPECT_NEAR(c.model_area, c.face_area, 1e-9 * c.face_area);
  EXPECT_NO_THROW(check_coverage(c, 0.0, "test"));
  EXPECT_EQ(coverage_message(c, "test"), "");
}

TEST(Coverage, AMissingPanelIsAGapOfItsArea) {
  const SurfaceFace f = plate();
  PanelMesh m = grid(7);
  m.panels.erase(m.panels.begin() + 24);  // an inner panel
  const Coverage c = measure_coverage(f, m, areas(m));
  const double panel = (kSize / 7) * (kSize / 7);
  // Scanline sampling across the gap: within one row spacing of its width.
  EXPECT_NEAR(c.gap, panel, 0.02 * panel);
  EXPECT_LT(c.overlap + c.outside, 1e-9 * c.face_area);
  EXPECT_NEAR(c.widest_gap, kSize / 7, 1e-6 * kSize);
  try {
    check_coverage(c, 0.0, "test");
    FAIL() << "a 2% gap must be refused";
  } catch (const GeometryFailure& e) {
    EXPECT_NE(std::string(e.what()).find("uncovered"), std::string::npos) << e.what();
  }
}

TEST(Coverage, ASlantedTriangularHoleIsMeasuredBothWays) {
  // Two triangles of one quad dropped, leaving a triangle of known area whose
  // hypotenuse runs diagonally across the scanlines.
  const SurfaceFace f = plate();
  PanelMesh m = grid(4);
  const std::vector<int> q = m.panels[5];
  m.panels[5] = {q[0], q[1], q[2]};  // keeps the lower-right half
  const Coverage c = measure_coverage(f, m, areas(m));
  const double half = 0.5 * (kSize / 4) * (kSize / 4);
  EXPECT_NEAR(c.gap, half, 0.01 * half);
}

TEST(Coverage, ADuplicatePanelIsAnOverlapAndSpillIsOutside) {
  const SurfaceFace f = plate();
  PanelMesh m = grid(5);
  m.panels.push_back(m.panels[7]);
  Coverage c = measure_coverage(f, m, areas(m));
  const double panel = (kSize / 5) * (kSize / 5);
  EXPECT_NEAR(c.overlap, panel, 0.02 * panel);
  EXPECT_LT(c.gap, 1e-9 * c.face_area);
  EXPECT_THROW(check_coverage(c, 0.0, "test"), GeometryFailure);

  // A panel beyond the plate's edge x = kSize: all of it outside.
  PanelMesh spill = grid(5);
  const int base = static_cast<int>(spill.uv.size());
  for (const Vec2& q :
       {Vec2(kSize, 0), Vec2(kSize + 200, 0), Vec2(kSize + 200, 200), Vec2(kSize, 200)}) {
    spill.uv.push_back(q);
    spill.xyz.push_back(Vec3(q.x(), q.y(), 0));
  }
  spill.panels.push_back({base, base + 1, base + 2, base + 3});
  c = measure_coverage(f, spill, areas(spill));
  EXPECT_NEAR(c.outside, 200.0 * 200.0, 0.02 * 200.0 * 200.0);
  EXPECT_GT(c.overlap_fraction(), kMaxCoverageError);
}

TEST(Coverage, ModelAreaBeyondTheOutlinesIsRefused) {
  // The (u,v) outlines tile the plate but one panel's 3D corners are lifted
  // far off it: the panels' 3D area exceeds what their outlines cover.
  const SurfaceFace f = plate();
  PanelMesh m = grid(4);
  m.xyz[6].z() = 2000.0;
  const Coverage c = measure_coverage(f, m, areas(m));
  EXPECT_LT(c.gap + c.overlap + c.outside, 1e-9 * c.face_area);
  EXPECT_GT(c.model_area, c.face_area * 1.1);
  try {
    check_coverage(c, 0.0, "test");
    FAIL() << "3D area over the covered area must be refused";
  } catch (const GeometryFailure& e) {
    EXPECT_NE(std::string(e.what()).find("overlap in space"), std::string::npos) << e.what();
  }
  // Within the deviation band it is accepted.
  EXPECT_NO_THROW(check_coverage(c, c.model_area, "test"));
}

TEST(ZeroAreaPanels, ACollinearTriangleIsMergedIntoItsNeighbour) {
  // Quad a-b-c-d with a degenerate triangle a-e-b on its bottom edge (e the
  // midpoint of a-b): the triangle goes, the quad takes e as an outline point.
  PanelMesh m;
  for (const Vec2& q : {Vec2(0, 0), Vec2(100, 0), Vec2(100, 100), Vec2(0, 100), Vec2(50, 0)}) {
    m.uv.push_back(q);
    m.xyz.push_back(Vec3(q.x(), q.y(), 0));
  }
  m.panels = {{0, 1, 2, 3}, {0, 4, 1}};
  m.nominal_area = 100.0 * 100.0;
  build_rods(m);
  EXPECT_EQ(remove_zero_area_panels(m, 200.0), 1);
  ASSERT_EQ(m.panels.size(), 1u);
  EXPECT_EQ(m.panels[0].size(), 5u);  // a, e, b, c, d
  EXPECT_NEAR(panel_area(m, 0), 100.0 * 100.0, 1e-9);
  for (const auto& rod : m.rods) EXPECT_NE(rod[0], rod[1]);
}

TEST(ZeroAreaPanels, AnIsolatedDegeneratePanelIsDroppedAndNothingElseChanges) {
  PanelMesh m = grid(3);
  const std::size_t before = m.panels.size();
  // A repeated-corner "panel" sharing no edge with the grid.
  const int base = static_cast<int>(m.uv.size());
  for (int k = 0; k < 3; ++k) {
    m.uv.push_back(Vec2(2000, 2000));
    m.xyz.push_back(Vec3(2000, 2000, 0));
  }
  m.panels.push_back({base, base + 1, base + 2});
  EXPECT_EQ(remove_zero_area_panels(m, 2000.0), 1);
  EXPECT_EQ(m.panels.size(), before);
  EXPECT_EQ(m.uv.size(), 16u);  // the dropped panel's vertices went with it
  PanelMesh untouched = grid(3);
  EXPECT_EQ(remove_zero_area_panels(untouched, 2000.0), 0);
  EXPECT_EQ(untouched.panels, grid(3).panels);
}

}  // namespace
}  // namespace tessella
