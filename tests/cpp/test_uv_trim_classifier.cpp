// The one (u,v) point-in-trim classifier: a square with a square hole, where
// the answer of every probe is known by construction.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "geometry/trim_deflection.h"
#include "geometry/uv_trim_classifier.h"
#include "test_faces.h"

using namespace tessella;
using namespace tessella::test;

namespace {

// [0,10]^2 counter-clockwise with the hole [4,6]^2 clockwise; a few extra
// points on the outer edges so edges and vertices are not all at the corners.
std::vector<std::vector<Vec2>> square_with_hole() {
  return {{{0, 0}, {5, 0}, {10, 0}, {10, 5}, {10, 10}, {0, 10}}, {{4, 4}, {4, 6}, {6, 6}, {6, 4}}};
}

UvTrimClassifier::Options eps(double e) {
  UvTrimClassifier::Options o;
  o.on_trim = e;
  return o;
}

}  // namespace

TEST(UvTrimClassifier, SquareWithHoleInsideOutside) {
  const UvTrimClassifier c(square_with_hole(), eps(1e-6));
  EXPECT_EQ(c.classify({1, 1}), TrimSide::Inside);
  EXPECT_EQ(c.classify({9, 9}), TrimSide::Inside);
  EXPECT_EQ(c.classify({5, 2}), TrimSide::Inside);
  EXPECT_EQ(c.classify({5, 5}), TrimSide::Outside);  // in the hole
  EXPECT_EQ(c.classify({4.5, 5.9}), TrimSide::Outside);
  EXPECT_EQ(c.classify({-1, 5}), TrimSide::Outside);
  EXPECT_EQ(c.classify({11, 5}), TrimSide::Outside);
  EXPECT_EQ(c.classify({5, -1e-3}), TrimSide::Outside);
  EXPECT_EQ(c.classify({5, 10 + 1e-3}), TrimSide::Outside);
  EXPECT_TRUE(c.contains(1, 1));
  EXPECT_FALSE(c.contains(5, 5));
}

TEST(UvTrimClassifier, EdgesAndVerticesAreOnTrimWithinEpsilon) {
  const double e = 1e-6;
  const UvTrimClassifier c(square_with_hole(), eps(e));
  for (const Vec2& p : std::vector<Vec2>{{0, 3},
                                         {10, 7},
                                         {2.5, 0},
                                         {3, 10},
                                         {4, 5},
                                         {6, 4.5},
                                         {5, 4},
                                         {5, 6},
                                         {0, 0},
                                         {10, 10},
                                         {5, 0},
                                         {10, 5},
                                         {4, 4},
                                         {6, 6},
                                         {0.5 * e, 3},
                                         {5, 6 - 0.9 * e},
                                         {-0.9 * e, -0.0}}) {
    EXPECT_EQ(c.classify(p), TrimSide::OnTrim) << p.transpose();
    EXPECT_TRUE(c.contains(p)) << p.transpose();
  }
  // Just beyond the epsilon the side is decided by parity.
  EXPECT_EQ(c.classify({2 * e, 3}), TrimSide::Inside);
  EXPECT_EQ(c.classify({-2 * e, 3}), TrimSide::Outside);
  EXPECT_EQ(c.classify({5, 6 - 2 * e}), TrimSide::Outside);
  EXPECT_EQ(c.classify({5, 6 + 2 * e}), TrimSide::Inside);
  // At a corner, the diagonal distance counts.
  EXPECT_EQ(c.classify({-0.8 * e, -0.8 * e}), TrimSide::Outside);
  EXPECT_EQ(c.classify({-0.7 * e, -0.7 * e}), TrimSide::OnTrim);
}

TEST(UvTrimClassifier, ZeroEpsilonStillReportsExactlyOnEdge) {
  const UvTrimClassifier c(square_with_hole(), eps(0));
  EXPECT_EQ(c.on_trim(), 0);
  EXPECT_EQ(c.classify({0, 3}), TrimSide::OnTrim);
  EXPECT_EQ(c.classify({6, 5}), TrimSide::OnTrim);
  EXPECT_EQ(c.classify({1e-12, 3}), TrimSide::Inside);
}

TEST(UvTrimClassifier, ScanlineThroughVerticesCountsThemOnce) {
  const UvTrimClassifier c(square_with_hole(), eps(1e-9));
  // v = 5 passes through the outer vertex (10, 5); v = 4 and 6 run along the
  // hole's horizontal edges through its vertices; v = 0 along the bottom edge.
  for (double v : {5.0, 4.0, 6.0, 0.0, 2.0}) {
    const std::vector<double> x = c.crossings(0, v);
    EXPECT_EQ(x.size() % 2, 0u) << "v = " << v;
    EXPECT_TRUE(std::is_sorted(x.begin(), x.end()));
  }
  EXPECT_EQ(c.crossings(0, 5.0), (std::vector<double>{0, 4, 6, 10}));
  EXPECT_EQ(c.crossings(0, 2.0), (std::vector<double>{0, 10}));
  // Half-open rule: the hole's bottom edge v = 4 starts its vertical edges,
  // its top edge v = 6 ends them.
  EXPECT_EQ(c.crossings(0, 4.0), (std::vector<double>{0, 4, 6, 10}));
  EXPECT_EQ(c.crossings(0, 6.0), (std::vector<double>{0, 10}));
  // Lines of fixed u, through the vertex (5, 0) and the hole's edge u = 4.
  EXPECT_EQ(c.crossings(1, 5.0), (std::vector<double>{0, 4, 6, 10}));
  EXPECT_EQ(c.crossings(1, 4.0), (std::vector<double>{0, 4, 6, 10}));
  EXPECT_TRUE(c.crossings(0, 10.5).empty());
  EXPECT_TRUE(c.crossings(1, -0.5).empty());
  // Points on a scanline through a vertex, off the trim.
  EXPECT_EQ(c.classify({2, 5}), TrimSide::Inside);
  EXPECT_EQ(c.classify({5, 5}), TrimSide::Outside);
  EXPECT_EQ(c.classify({8, 5}), TrimSide::Inside);
  EXPECT_EQ(c.classify({12, 5}), TrimSide::Outside);
}

TEST(UvTrimClassifier, ClassifyAgreesWithCrossingsAndIsDeterministic) {
  const UvTrimClassifier a(square_with_hole(), eps(1e-9));
  const UvTrimClassifier b(square_with_hole(), eps(1e-9));
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> d(-1, 11);
  for (int k = 0; k < 20000; ++k) {
    const Vec2 p(d(rng), d(rng));
    const TrimSide s = a.classify(p);
    EXPECT_EQ(s, b.classify(p));
    EXPECT_EQ(s, a.classify(p));
    const bool hole = p.x() > 4 && p.x() < 6 && p.y() > 4 && p.y() < 6;
    const bool square = p.x() > 0 && p.x() < 10 && p.y() > 0 && p.y() < 10;
    if (s != TrimSide::OnTrim) {
      EXPECT_EQ(s == TrimSide::Inside, square && !hole) << p.transpose();
    }
    // The scanline's parity below p says the same.
    const std::vector<double> x = a.crossings(0, p.y());
    const auto below = std::lower_bound(x.begin(), x.end(), p.x()) - x.begin();
    if (s != TrimSide::OnTrim) {
      EXPECT_EQ(below % 2 == 1, s == TrimSide::Inside);
    }
  }
}

TEST(UvTrimClassifier, EmptyIsOutsideAndDefaultEpsilonIsRelative) {
  const UvTrimClassifier none;
  EXPECT_TRUE(none.empty());
  EXPECT_EQ(none.classify({0, 0}), TrimSide::Outside);
  EXPECT_TRUE(none.crossings(0, 0).empty());
  const UvTrimClassifier c(square_with_hole());
  EXPECT_DOUBLE_EQ(c.on_trim(), 1e-9 * std::hypot(10.0, 10.0));
}

TEST(UvTrimClassifier, OcctCrossCheckOnARealFace) {
  const SurfaceFace face = plate_with_square_hole(100, 40, 60);
  const std::vector<TrimLoop> loops = face.trim_loops(automatic_trim_deflection(face));
  UvTrimClassifier::Options o;
  o.check_with = &face;
  const UvTrimClassifier c(loops, o);
  EXPECT_FALSE(c.uses_occt());
  for (double u = 1; u < 100; u += 7)
    for (double v = 1; v < 100; v += 7) {
      // The plate's (u,v) is its (x,y) up to OCCT's parameterization of the
      // plane: compare with OCCT directly.
      EXPECT_EQ(c.contains(u, v), face.is_inside(u, v)) << u << " " << v;
    }
  // Loops that do not describe the face: the cross-check sends queries to OCCT.
  const UvTrimClassifier wrong(std::vector<std::vector<Vec2>>{{{0, 0}, {1, 0}, {1, 1}}}, o);
  EXPECT_TRUE(wrong.uses_occt());
  EXPECT_EQ(wrong.contains(50, 20), face.is_inside(50, 20));
}

TEST(TrimDeflection, OneRuleFromTheModelSize) {
  const SurfaceFace face = plate_with_square_hole(100, 40, 60);
  EXPECT_DOUBLE_EQ(automatic_trim_deflection(face), kAutomaticTrimDeflection * face.model_size());
  EXPECT_DOUBLE_EQ(trim_deflection(face, 0.0), automatic_trim_deflection(face));
  EXPECT_DOUBLE_EQ(trim_deflection(face, 0.25), 0.25);
}
