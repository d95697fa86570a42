// boundary_driven across faces on different surfaces joined smoothly
// (bd_across_surfaces.h, trace_bd_curves_across): the pieces on planar
// plates, where the expected curves are straight lines known in closed form.
#include <gtest/gtest.h>

#include <BRepBuilderAPI_MakeFace.hxx>
#include <algorithm>
#include <cmath>
#include <gp_Pln.hxx>

#include "methods/boundary_driven/bd_across_surfaces.h"
#include "methods/boundary_driven/bd_curves.h"
#include "methods/boundary_driven/bd_sources.h"
#include "methods/boundary_driven/bd_tensor.h"
#include "tessella/errors.h"
#include "test_faces.h"

using namespace tessella;
using namespace tessella::test;

namespace {

// The plate [x0, x1] x [0, h] on z = 0.
SurfaceFace plate(double x0, double x1, double h) {
  BRepBuilderAPI_MakeFace mk(gp_Pln(), rect_wire(x0, 0, x1, h, false));
  return SurfaceFace::from_brep_string(brep(mk.Face()));
}

std::vector<BdPolyline> trims(const SurfaceFace& f) {
  return select_bd_sources(f, f.trim_loops(1e-4), {}).boundary;
}

EdgeTrack segment(const Vec3& a, const Vec3& b) { return EdgeTrack({a, b}); }

bool contains(const std::vector<Vec3>& points, const Vec3& p, double tol) {
  return std::any_of(points.begin(), points.end(),
                     [&](const Vec3& q) { return (q - p).norm() <= tol; });
}

}  // namespace

TEST(EdgeTrack, NearMeansWithinTheDistanceOfSomeSegment) {
  std::vector<Vec3> pts;
  for (int k = 0; k <= 200; ++k) pts.push_back(Vec3(10.0 * k, 0, 0));  // several boxes
  const EdgeTrack t(pts);
  EXPECT_TRUE(t.near(Vec3(1234.5, 0.9, 0), 1.0));
  EXPECT_FALSE(t.near(Vec3(1234.5, 1.1, 0), 1.0));
  EXPECT_TRUE(t.near(Vec3(-0.5, 0, 0), 1.0));  // beyond the first end
  EXPECT_FALSE(t.near(Vec3(-1.5, 0, 0), 1.0));
  EXPECT_TRUE(t.near(Vec3(2000, 0, 0.99), 1.0));  // the last end
  std::size_t seg = 0;
  double along = 0;
  ASSERT_TRUE(t.nearest(Vec3(1234.5, 0.5, 0), 1.0, seg, along));
  EXPECT_EQ(seg, 123u);
  EXPECT_NEAR(along, 0.45, 1e-12);
  EXPECT_FALSE(t.nearest(Vec3(1234.5, 1.5, 0), 1.0, seg, along));
}

TEST(EdgeTrack, SampleCurveDoublesUntilTheSagIsSmallEnough) {
  // A circle of radius 1000: a chord of angle a sags 1000 (1 - cos(a / 2)).
  const auto at = [](double t) { return Vec3(1000 * std::cos(t), 1000 * std::sin(t), 0); };
  const double last = 3.0;
  double sag = 0;
  const std::vector<Vec3> line = sample_curve(at, 0.0, last, 0.05, 1 << 20, sag);
  const int n = static_cast<int>(line.size()) - 1;
  const double expected = [&](int chords) {
    return 1000 * (1 - std::cos(0.5 * last / chords));
  }(n);
  EXPECT_NEAR(sag, expected, 1e-9);
  EXPECT_LE(sag, 0.05);
  EXPECT_GT(1000 * (1 - std::cos(0.5 * last / (n / 2))), 0.05);  // half as many would not do
  EXPECT_EQ(n % 64, 0);
  // The points are the curve's at uniform parameters, bit for bit.
  for (int k = 0; k <= n; ++k) EXPECT_EQ(line[k], at(0.0 + last * k / n)) << k;
  // Capped: 64 chords when no more are allowed.
  EXPECT_EQ(sample_curve(at, 0.0, last, 1e-9, 64, sag).size(), 65u);
  const std::vector<EdgeTrack> tracks{EdgeTrack({Vec3(0, 0, 0), Vec3(10, 0, 0)}),
                                      EdgeTrack({Vec3(0, 5, 0), Vec3(10, 5, 0)})};
  EXPECT_EQ(first_track_near(tracks, Vec3(5, 4.5, 0), 1.0), 1);
  EXPECT_EQ(first_track_near(tracks, Vec3(5, 2.5, 0), 1.0), -1);
}

TEST(BdFreeBoundary, ASquareLessOneSideIsOneOpenRunOfThreeSides) {
  const SurfaceFace f = plate(0, 4000, 4000);
  const std::vector<BdPolyline> boundary = trims(f);
  ASSERT_EQ(boundary.size(), 1u);
  // Skip the side x = 4000.
  const auto runs =
      bd_free_boundary_runs(boundary, {segment(Vec3(4000, 0, 0), Vec3(4000, 4000, 0))}, 1e-3);
  ASSERT_EQ(runs.size(), 1u);
  EXPECT_FALSE(runs[0].closed);
  EXPECT_NEAR(runs[0].length(), 12000.0, 1e-6);
  // It keeps the two corners where it meets the skipped side.
  EXPECT_NEAR(runs[0].xyz.front().x(), 4000.0, 1e-9);
  EXPECT_NEAR(runs[0].xyz.back().x(), 4000.0, 1e-9);
  // Nothing skipped: the loop itself; all skipped: nothing.
  EXPECT_TRUE(bd_free_boundary_runs(boundary, {}, 1e-3)[0].closed);
  std::vector<EdgeTrack> all;
  for (int k = 0; k < 4; ++k) {
    const double x[5] = {0, 4000, 4000, 0, 0}, y[5] = {0, 0, 4000, 4000, 0};
    all.push_back(segment(Vec3(x[k], y[k], 0), Vec3(x[k + 1], y[k + 1], 0)));
  }
  EXPECT_TRUE(bd_free_boundary_runs(boundary, all, 1e-3).empty());
}

TEST(BdChainSeeds, TwoHalvesOfASquareGiveTheSquaresSeedsInAnyOrder) {
  // The square [0, 4000]^2 split at x = 2000 into two faces: each face's run
  // is its three free sides; joined, they are the square's boundary, whose
  // seeds are every 1000 mm between its four corners (12), as one face has.
  const SurfaceFace left = plate(0, 2000, 4000), right = plate(2000, 4000, 4000);
  const EdgeTrack cut = segment(Vec3(2000, 0, 0), Vec3(2000, 4000, 0));
  std::vector<BdPolyline> runs = bd_free_boundary_runs(trims(left), {cut}, 1e-3);
  const std::vector<BdPolyline> r = bd_free_boundary_runs(trims(right), {cut}, 1e-3);
  runs.insert(runs.end(), r.begin(), r.end());
  ASSERT_EQ(runs.size(), 2u);
  const std::vector<Vec3> seeds = bd_chain_seeds(runs, 1000.0, 30.0, 1e-3);
  ASSERT_EQ(seeds.size(), 12u);
  for (double t : {1000.0, 2000.0, 3000.0}) {
    for (const Vec3& p : {Vec3(t, 0, 0), Vec3(t, 4000, 0), Vec3(0, t, 0), Vec3(4000, t, 0)})
      EXPECT_TRUE(contains(seeds, p, 1e-6)) << p.transpose();
  }
  // The runs listed the other way round, one reversed: the same seeds, in
  // the same order (the chain starts at its least point).
  std::vector<BdPolyline> other = {runs[1], runs[0]};
  std::reverse(other[0].xyz.begin(), other[0].xyz.end());
  std::reverse(other[0].uv.begin(), other[0].uv.end());
  finish_polyline(other[0]);
  const std::vector<Vec3> again = bd_chain_seeds(other, 1000.0, 30.0, 1e-3);
  ASSERT_EQ(again.size(), seeds.size());
  // The chain may run the other way round: the same points, either order.
  std::vector<Vec3> backward(again.rbegin(), again.rend());
  bool same = true, reversed = true;
  for (std::size_t k = 0; k < seeds.size(); ++k) {
    same = same && (again[k] - seeds[k]).norm() < 1e-6;
    reversed = reversed && contains(seeds, again[k], 1e-6);
  }
  EXPECT_TRUE(same || reversed);
}

TEST(BdCurvesAcross, OneChartWithoutSmoothEdgesTracesAsOneFace) {
  const SurfaceFace f = plate(0, 4000, 3000);
  const std::vector<BdPolyline> boundary = trims(f);
  BdTensorParams tp;
  tp.sample_spacing = 250;
  const BdTensor tensor = build_bd_tensor(f, boundary, tp);
  BdCurveParams cp;
  cp.spacing = 1000;
  const std::vector<BdCurve> one = trace_bd_curves(f, tensor, boundary, cp);
  BdChart chart;
  chart.face = &f;
  chart.boundary = &boundary;
  const std::vector<std::vector<BdCurve>> across = trace_bd_curves_across({chart}, tensor, cp);
  ASSERT_EQ(across.size(), 1u);
  ASSERT_EQ(across[0].size(), one.size());
  for (std::size_t c = 0; c < one.size(); ++c) {
    ASSERT_EQ(across[0][c].uv.size(), one[c].uv.size());
    for (std::size_t i = 0; i < one[c].uv.size(); ++i) EXPECT_EQ(across[0][c].uv[i], one[c].uv[i]);
    EXPECT_EQ(across[0][c].start.loop, one[c].start.loop);
    EXPECT_EQ(across[0][c].end.s, one[c].end.s);
  }
}

TEST(BdCurvesAcross, CurvesRunOnAcrossASmoothEdgeIntoTheFaceBeyond) {
  // Two plates side by side, [0, 2500] and [2500, 6000] x [0, 3000], each
  // its own face: traced as a group (sources: the outer boundary; seeds
  // along it), every curve that meets the edge x = 2500 goes on into the
  // other plate at the same point, as one straight line y = const.
  const SurfaceFace left = plate(0, 2500, 3000), right = plate(2500, 6000, 3000);
  const EdgeTrack cut = segment(Vec3(2500, 0, 0), Vec3(2500, 3000, 0));
  BoundaryDrivenParams params;
  params.size = 500;  // quadrangulated: curves 1000 mm apart
  std::vector<BdGroupMember> members = {bd_group_member(left, params),
                                        bd_group_member(right, params)};
  members[0].smooth = {cut};
  members[0].smooth_to = {1};
  members[1].smooth = {cut};
  members[1].smooth_to = {0};
  const BdGroupCurves g = trace_bd_group_curves(members, params);
  ASSERT_EQ(g.curves.size(), 2u);
  EXPECT_DOUBLE_EQ(g.spacing, 1000.0);
  auto on_cut = [](const Vec3& p) { return std::abs(p.x() - 2500) < 1e-6; };
  std::vector<Vec3> left_ends, right_starts;
  for (int side = 0; side < 2; ++side)
    for (const BdCurve& c : g.curves[static_cast<std::size_t>(side)]) {
      // Straight lines of the field of a rectangle: x or y constant.
      const Vec3 a = c.xyz.front(), b = c.xyz.back();
      EXPECT_TRUE(std::abs(a.x() - b.x()) < 1e-6 || std::abs(a.y() - b.y()) < 1e-6)
          << a.transpose() << " / " << b.transpose();
      for (const Vec3& end : {a, b})
        if (on_cut(end)) (side == 0 ? left_ends : right_starts).push_back(end);
    }
  // Rows every 1000 mm (y = 1000, 2000), each crossing once, on both sides.
  ASSERT_EQ(left_ends.size(), 2u);
  ASSERT_EQ(right_starts.size(), 2u);
  for (const Vec3& p : left_ends) {
    EXPECT_TRUE(contains(right_starts, p, 1e-6)) << p.transpose();
    EXPECT_NEAR(std::fmod(p.y() + 1e-9, 1000.0), 0.0, 1e-6);
  }
  // The seam between the plates is no trim: no curve runs along it.
  for (const auto& side : g.curves)
    for (const BdCurve& c : side) EXPECT_FALSE(on_cut(c.xyz.front()) && on_cut(c.xyz.back()));
  // Closed on itself (no free boundary): nothing to start from.
  std::vector<BdGroupMember> closed = members;
  for (BdGroupMember& m : closed)
    for (int k = 0; k < 4; ++k) {
      const double x0 = m.face == &left ? 0 : 2500, x1 = m.face == &left ? 2500 : 6000;
      const double x[5] = {x0, x1, x1, x0, x0}, y[5] = {0, 0, 3000, 3000, 0};
      m.smooth.push_back(segment(Vec3(x[k], y[k], 0), Vec3(x[k + 1], y[k + 1], 0)));
      m.smooth_to.push_back(m.face == &left ? 1 : 0);
    }
  EXPECT_THROW(trace_bd_group_curves(closed, params), GeometryFailure);
}
