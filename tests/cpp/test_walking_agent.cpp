// Closed-form checks of the agent methods of seed 000: walking_agent,
// gradient_descent, relaxed_grid.
#include <gtest/gtest.h>

#include <BRepBuilderAPI_MakeFace.hxx>
#include <Geom_SphericalSurface.hxx>
#include <algorithm>
#include <cmath>
#include <gp_Ax3.hxx>
#include <set>

#include "mesh/panel_model.h"
#include "tessella/errors.h"
#include "tessella/panel_metrics.h"
#include "tessella/relaxed_grid.h"
#include "tessella/walking_agent.h"
#include "test_faces.h"

using namespace tessella;
using namespace tessella::test;

namespace {
constexpr double kPi = 3.14159265358979323846;

// Distinct ring angles (radians, [0, 2pi)) and heights of a cylinder mesh.
std::vector<double> sorted_unique(std::vector<double> x, double tol) {
  std::sort(x.begin(), x.end());
  std::vector<double> out;
  for (double v : x)
    if (out.empty() || v - out.back() > tol) out.push_back(v);
  return out;
}
std::vector<double> angles(const PanelMesh& m) {
  std::vector<double> a;
  for (const Vec3& p : m.xyz) {
    double t = std::atan2(p.y(), p.x());
    if (t < -1e-12) t += 2 * kPi;
    a.push_back(std::max(t, 0.0));
  }
  return sorted_unique(a, 1e-9);
}
std::vector<double> heights(const PanelMesh& m) {
  std::vector<double> z;
  for (const Vec3& p : m.xyz) z.push_back(p.z());
  return sorted_unique(z, 1e-6);
}

WalkingAgentParams agent(double bound) {
  WalkingAgentParams p;
  p.max_deviation = bound;
  return p;
}

double max_of(const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); }
}  // namespace

// On a cylinder of radius R the chord of angle t deviates R (1 - cos(t / 2)).
// The agent steps 0.05 x 2 pi = 18 degrees, steps back by 1.8 degrees: the
// longest multiple of 1.8 degrees within the bound 20 mm at R = 5000 is 9
// degrees (10.8 would give 22.2 mm), so the ring has exactly 40 equal panels.
TEST(WalkingAgent, CylinderPanelAngleIsTheLongestTenthStepWithinTheBound) {
  const double r = 5000, bound = 20;
  const SurfaceFace f = cylinder_face(r, 8000);
  const double tenth = 0.1 * 0.05 * 2 * kPi;
  int k = 1;
  while (r * (1 - std::cos((k + 1) * tenth / 2)) <= bound) ++k;
  ASSERT_EQ(k, 5);  // 9 degrees
  WalkingAgentParams p = agent(bound);
  p.iso_fallback = false;  // the agents' own rule (the fallback: next test)
  const PanelMesh m = walking_agent(f, p);
  const std::vector<double> a = angles(m);
  ASSERT_EQ(a.size(), 40u);
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double next = i + 1 < a.size() ? a[i + 1] : 2 * kPi;
    EXPECT_NEAR(next - a[i], k * tenth, 1e-9);
  }
  // The generatrix is straight: one panel high (no max_size).
  EXPECT_EQ(heights(m).size(), 2u);
  EXPECT_EQ(m.panels.size(), 40u);
  // The measured panel deviation is the sagitta of the 9-degree chord.
  const PanelMetrics pm = measure_panels(f, m);
  EXPECT_NEAR(max_of(pm.deviation), r * (1 - std::cos(k * tenth / 2)), 1e-6 * r);
}

// The bound is a bound for every value: R (1 - cos(theta / 2)) <= bound for the
// widest panel, whatever the bound and the sample step.
TEST(WalkingAgent, CylinderBoundHoldsForEveryBoundAndStep) {
  const double r = 3000;
  const SurfaceFace f = cylinder_face(r, 2000);
  for (double bound : {1.0, 7.5, 60.0}) {
    for (double step : {0.01, 0.05, 0.1}) {
      WalkingAgentParams p = agent(bound);
      p.sample_step = step;
      const PanelMesh m = walking_agent(f, p);
      const std::vector<double> a = angles(m);
      double widest = 0;
      for (std::size_t i = 0; i < a.size(); ++i)
        widest = std::max(widest, (i + 1 < a.size() ? a[i + 1] : 2 * kPi) - a[i]);
      EXPECT_LE(r * (1 - std::cos(widest / 2)), bound * (1 + 1e-9)) << bound << " " << step;
      EXPECT_LE(max_of(measure_panels(f, m).deviation), bound) << bound << " " << step;
    }
  }
}

// max_size: on the straight generatrix the agent steps 400 mm, breaks the
// 3000 mm limit at 3200 and steps back by tenths (40 mm) to 3000.
TEST(WalkingAgent, MaxSizeStepsBackToTheLimit) {
  const SurfaceFace f = cylinder_face(5000, 8000);
  WalkingAgentParams p = agent(20);
  p.max_size = 3000;
  p.iso_fallback = false;
  const std::vector<double> z = heights(walking_agent(f, p));
  ASSERT_EQ(z.size(), 4u);
  EXPECT_NEAR(z[1], 3000, 1e-6);
  EXPECT_NEAR(z[2], 6000, 1e-6);
  EXPECT_NEAR(z[3], 8000, 1e-6);
}

// Where curvature is even the agents' tenth steps cost panels: on the
// cylinder (R = 5000, bound 20 mm, checked at 0.98 x the bound) 9-degree
// steps make 40 panels, while n equal panels hold it for the least n with
// R (1 - cos(pi / n)) <= 19.6: n = 36. The fallback keeps that grid, one
// panel high (ceil(8000 / max_size) with a max_size).
TEST(WalkingAgent, EvenCurvatureFallsBackToTheCoarsestIsoGrid) {
  const double r = 5000, bound = 20;
  const SurfaceFace f = cylinder_face(r, 8000);
  int n = 3;
  while (r * (1 - std::cos(kPi / n)) > 0.98 * bound) ++n;
  ASSERT_EQ(n, 36);
  WalkingAgentReport rep;
  const PanelMesh m = walking_agent(f, agent(bound), &rep);
  EXPECT_EQ(rep.iso_u_count * rep.iso_v_count, 36);
  const std::vector<double> a = angles(m);
  ASSERT_EQ(a.size(), 36u);
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double next = i + 1 < a.size() ? a[i + 1] : 2 * kPi;
    EXPECT_NEAR(next - a[i], 2 * kPi / 36, 1e-9);
  }
  EXPECT_EQ(m.panels.size(), 36u);
  EXPECT_LE(max_of(measure_panels(f, m).deviation), bound);
  // With max_size 3000 mm: three rows of 8000 / 3 mm.
  WalkingAgentParams p = agent(bound);
  p.max_size = 3000;
  const PanelMesh limited = walking_agent(f, p);
  const std::vector<double> z = heights(limited);
  ASSERT_EQ(z.size(), 4u);
  EXPECT_NEAR(z[1], 8000.0 / 3, 1e-6);
  EXPECT_EQ(limited.panels.size(), 108u);
}

TEST(WalkingAgent, EveryStartKeepsTheBoundOnADoublyCurvedPatch) {
  const SurfaceFace f = sphere_face(4000);
  for (const char* start :
       {"u_min_v_min", "u_max_v_min", "u_min_v_max", "u_max_v_max", "max_curvature"}) {
    WalkingAgentParams p = agent(25);
    p.start = start;
    WalkingAgentReport rep;
    const PanelMesh m = walking_agent(f, p, &rep);
    ASSERT_FALSE(m.panels.empty());
    EXPECT_LE(max_of(measure_panels(f, m).deviation), 25.0) << start;
    EXPECT_LE(rep.max_estimate, 25.0) << start;
    // Folds are recorded as diagonals shared by two triangles.
    EXPECT_EQ(static_cast<int>(m.folds.size()), rep.folds);
  }
}

TEST(WalkingAgent, TrimmedPlateIsCutByTheHoleAndCoversTheFace) {
  const SurfaceFace f = plate_with_square_hole(1000, 300, 600);
  WalkingAgentParams p = agent(1);
  p.max_size = 250;
  const PanelMesh m = walking_agent(f, p);
  double area = 0;
  for (std::size_t k = 0; k < m.panels.size(); ++k) area += panel_area(m, k);
  EXPECT_NEAR(area, 1000.0 * 1000.0 - 300.0 * 300.0, 1e-6 * 1e6);
  for (const Vec2& q : m.uv) EXPECT_TRUE(f.is_inside(q.x(), q.y()));
  EXPECT_EQ(max_of(measure_panels(f, m).deviation), 0.0);
}

TEST(WalkingAgent, BadParametersNameThemselves) {
  const SurfaceFace f = cylinder_face(1000, 1000);
  auto message = [&](WalkingAgentParams p) {
    try {
      walking_agent(f, p);
    } catch (const InvalidParameter& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message(WalkingAgentParams{}).find("max_deviation"), std::string::npos);
  WalkingAgentParams p = agent(-1);
  EXPECT_NE(message(p).find("max_deviation"), std::string::npos);
  p = agent(1);
  p.sample_step = 0.9;
  EXPECT_NE(message(p).find("sample_step"), std::string::npos);
  p = agent(1);
  p.start = "middle";
  EXPECT_NE(message(p).find("start"), std::string::npos);
  p = agent(1);
  p.max_size = -3;
  EXPECT_NE(message(p).find("max_size"), std::string::npos);
  p = agent(1);
  p.diagonal_deviation = -3;
  EXPECT_NE(message(p).find("diagonal_deviation"), std::string::npos);
}

// Thesis 5.2: the first step is taken arbitrarily (one sample step), the next
// is bound * (S1 + S2) / (E1 + E2). On a cylinder E(t) = R (1 - cos(t / 2)).
TEST(GradientDescent, CylinderStepsFollowTheThesisRuleAndOvershoot) {
  const double r = 5000, bound = 20;
  const SurfaceFace f = cylinder_face(r, 1000);
  GradientDescentParams p;
  p.max_deviation = bound;
  const PanelMesh m = gradient_descent(f, p);
  const std::vector<double> a = angles(m);
  ASSERT_GE(a.size(), 4u);
  auto E = [&](double t) { return r * (1 - std::cos(t / 2)); };
  const double s1 = 0.05 * 2 * kPi;
  EXPECT_NEAR(a[1] - a[0], s1, 1e-9);
  const double s2 = bound * s1 / E(s1);
  EXPECT_NEAR(a[2] - a[1], s2, 1e-9);
  const double s3 = bound * (s2 + s1) / (E(s2) + E(s1));
  EXPECT_NEAR(a[3] - a[2], s3, 1e-9);
  // The arbitrary first step already breaks the bound: E(18 deg) = 61.6 mm.
  EXPECT_GT(max_of(measure_panels(f, m).deviation), 3 * bound);
}

TEST(RelaxedGrid, CylinderStaysUniformAndKeepsItsTopology) {
  const double r = 5000;
  const SurfaceFace f = cylinder_face(r, 2000);
  RelaxedGridParams p;
  p.u_count = 24;
  p.v_count = 3;
  RelaxedGridReport rep;
  const PanelMesh m = relaxed_grid(f, p, &rep);
  EXPECT_TRUE(rep.converged);
  EXPECT_EQ(m.panels.size(), 72u);
  EXPECT_EQ(m.vertex_count(), 24u * 4u);  // seam welded
  EXPECT_NEAR(max_of(measure_panels(f, m).deviation), r * (1 - std::cos(kPi / 24)), 1e-6 * r);
}

// A parabolic cylinder z = x^2 / 1000, x in [0, 1500], parameterized by
// x = 1500 u^2 (a quartic Bezier): the uniform u grid has short rods near x = 0
// and long, strongly bent ones far out. Relaxation pulls nodes towards the bent
// rods, evening out the rod deviations without changing the number of panels.
TEST(RelaxedGrid, RelaxationEvensOutTheRodDeviation) {
  TColgp_Array2OfPnt poles(1, 5, 1, 2);
  const double xs[5] = {0, 0, 1500.0 / 6, 1500.0 / 2, 1500};
  const double zs[5] = {0, 0, 0, 0, 2250};
  for (int i = 1; i <= 5; ++i) {
    poles(i, 1) = gp_Pnt(xs[i - 1], 0, zs[i - 1]);
    poles(i, 2) = gp_Pnt(xs[i - 1], 1000, zs[i - 1]);
  }
  Handle(Geom_BezierSurface) s = new Geom_BezierSurface(poles);
  const SurfaceFace f =
      SurfaceFace::from_brep_string(brep(BRepBuilderAPI_MakeFace(s, 1e-7).Face()));
  RelaxedGridParams p;
  p.u_count = 12;
  p.v_count = 1;
  p.max_iterations = 0;
  const PanelMetrics before = measure_panels(f, relaxed_grid(f, p));
  p.max_iterations = 500;
  p.tolerance = 1e-7;
  const PanelMesh relaxed = relaxed_grid(f, p);
  const PanelMetrics after = measure_panels(f, relaxed);
  EXPECT_EQ(relaxed.panels.size(), 12u);
  auto spread = [](const std::vector<double>& d) {
    return max_of(d) / *std::min_element(d.begin(), d.end());
  };
  EXPECT_LT(spread(after.deviation), 0.5 * spread(before.deviation));
  EXPECT_LT(max_of(after.deviation), max_of(before.deviation));
}

TEST(SurfaceFace, CountsEvaluations) {
  const SurfaceFace f = cylinder_face(1000, 1000);
  f.reset_evaluations();
  f.point(0.1, 10);
  f.derivatives(0.2, 20);
  EXPECT_EQ(f.evaluations(), 2u);
  f.reset_evaluations();
  EXPECT_EQ(f.evaluations(), 0u);
}

namespace {
// A sphere zone from u0 to u1 (radians), latitudes -0.3 to 0.9.
SurfaceFace sphere_zone(double u0, double u1) {
  const Handle(Geom_SphericalSurface) s = new Geom_SphericalSurface(gp_Ax3(), 6000.0);
  return SurfaceFace::from_brep_string(brep(BRepBuilderAPI_MakeFace(s, u0, u1, -0.3, 0.9, 1e-7)));
}
bool contains_value(const std::vector<double>& xs, double x, double tol) {
  return std::any_of(xs.begin(), xs.end(), [&](double y) { return std::abs(x - y) <= tol; });
}
}  // namespace

// Faces of one surface walk their lines on their union (issue 14): a cut
// along an iso-line becomes a line, and a face cut from the union takes the
// union's lines within its bounds, so its rows continue those of its
// neighbour.
TEST(WalkingAgent, FacesCutFromOneSurfaceShareTheUnionsLinesAndTheCutIsOne) {
  const SurfaceFace whole = sphere_zone(0.0, 1.2);
  const WalkingAgentParams p = agent(15.0);
  const double cut = 0.5;
  const WalkingAgentLines free = walking_agent_lines(whole, p);
  EXPECT_FALSE(contains_value(free.u, cut, 1e-12));  // else the test proves nothing
  const WalkingAgentLines lines = walking_agent_lines(whole, p, {{cut}, {}});
  ASSERT_TRUE(contains_value(lines.u, cut, 0.0));
  EXPECT_TRUE(std::is_sorted(lines.u.begin(), lines.u.end()));
  EXPECT_EQ(lines.u.front(), 0.0);
  EXPECT_EQ(lines.u.back(), 1.2);
  // At most one line moved or added per pinned value: the others stay.
  int kept = 0;
  for (double x : free.u) kept += contains_value(lines.u, x, 0.0) ? 1 : 0;
  EXPECT_GE(kept, static_cast<int>(free.u.size()) - 1);

  for (const auto& [u0, u1] : {std::pair{0.0, cut}, std::pair{cut, 1.2}}) {
    const SurfaceFace part = sphere_zone(u0, u1);
    const PanelMesh m = walking_agent_on_lines(part, p, lines);
    ASSERT_FALSE(m.panels.empty());
    // Every union line within the part is a line of its panels' corners
    // (a node at each of its crossings with the part's v = -0.3 edge).
    for (double x : lines.u) {
      if (x < u0 - 1e-12 || x > u1 + 1e-12) continue;
      bool found = false;
      for (std::size_t v = 0; v < m.xyz.size(); ++v)
        found = found || (std::abs(m.uv[v].x() - x) <= 1e-9 && std::abs(m.uv[v].y() + 0.3) <= 1e-9);
      EXPECT_TRUE(found) << "line u = " << x << " on [" << u0 << ", " << u1 << "]";
    }
    // The hard bound holds on the part as on any face.
    const PanelMetrics metrics = measure_panels(part, m);
    EXPECT_LE(max_of(metrics.deviation), 15.0);
  }
  EXPECT_THROW(walking_agent_on_lines(whole, p, {{0.0}, {-0.3, 0.9}}), InvalidParameter);
}
