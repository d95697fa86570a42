// Panel types: hand-made outlines whose grouping is known by construction.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tessella/errors.h"
#include "tessella/panel_types.h"

using namespace tessella;

namespace {

using Outline = std::vector<Vec2>;

constexpr double kPi = 3.14159265358979323846;

// Rectangle w x h, counter-clockwise, corner 0 at `o`, turned by `deg`.
Outline rectangle(double w, double h, double deg = 0.0, Vec2 o = Vec2(0, 0)) {
  const double c = std::cos(deg * kPi / 180), s = std::sin(deg * kPi / 180);
  Outline p;
  for (const Vec2& q : {Vec2(0, 0), Vec2(w, 0), Vec2(w, h), Vec2(0, h)})
    p.push_back(o + Vec2(c * q.x() - s * q.y(), s * q.x() + c * q.y()));
  return p;
}

// A right trapezoid with no mirror symmetry (counter-clockwise).
Outline trapezoid() { return {{0, 0}, {400, 0}, {300, 200}, {0, 200}}; }

// Its mirror image (x -> -x), corners reordered to run counter-clockwise again.
Outline mirrored(const Outline& p) {
  Outline m;
  for (auto it = p.rbegin(); it != p.rend(); ++it) m.emplace_back(-it->x(), it->y());
  return m;
}

// The same outline starting at corner `k` (the panel turned in its plane).
Outline start_at(const Outline& p, std::size_t k) {
  Outline q;
  for (std::size_t i = 0; i < p.size(); ++i) q.push_back(p[(i + k) % p.size()]);
  return q;
}

PanelTypes types_of(const std::vector<Outline>& outlines, std::vector<double> folds = {},
                    PanelTypeParams p = {}) {
  if (folds.empty()) folds.assign(outlines.size(), 0.0);
  return panel_types(outlines, folds, p);
}

}  // namespace

TEST(PanelTypes, TurnedAndMovedPanelsShareATypeMirrorImagesDoNot) {
  const Outline t = trapezoid();
  Outline moved;
  for (const Vec2& q : start_at(t, 2)) moved.push_back(Vec2(-q.y(), q.x()) + Vec2(50, -70));
  const PanelTypes r = types_of({t, moved, mirrored(t), start_at(mirrored(t), 1)});
  EXPECT_EQ(r.type, (std::vector<int>{0, 0, 1, 1}));
  EXPECT_EQ(r.representative, (std::vector<int>{0, 2}));
  EXPECT_EQ(r.count(), 2);
}

TEST(PanelTypes, SymmetricPanelsAreTheirOwnMirrorImage) {
  const Outline sq = rectangle(300, 300, 17.0);
  const PanelTypes r = types_of({sq, mirrored(sq), rectangle(300, 200), rectangle(200, 300)});
  // A rectangle turned by 90 degrees is the same rectangle.
  EXPECT_EQ(r.type, (std::vector<int>{0, 0, 1, 1}));
}

TEST(PanelTypes, GreedyJoinsTheFirstTypeWithinToleranceOfItsFirstPanel) {
  // 100, 100.8 (within 1 of 100), 101.6 (within 1 of 100.8 but not of 100),
  // 100.4 (within 1 of both types' first panels: the first type wins).
  const PanelTypes r =
      types_of({rectangle(100, 100), rectangle(100.8, 100.8), rectangle(101.6, 101.6),
                rectangle(100.4, 100.4), rectangle(101.9, 101.9)});
  EXPECT_EQ(r.type, (std::vector<int>{0, 0, 1, 0, 1}));
  EXPECT_EQ(r.representative, (std::vector<int>{0, 2}));
}

TEST(PanelTypes, ToleranceIsInclusiveAndZeroMeansEqual) {
  PanelTypeParams exact;
  exact.length_tol = 0.0;
  exact.angle_tol = 0.0;
  EXPECT_EQ(
      types_of({rectangle(128, 64), rectangle(128, 64), rectangle(128, 64.5)}, {}, exact).type,
      (std::vector<int>{0, 0, 1}));
  PanelTypeParams half;
  half.length_tol = 0.5;  // 64 and 64.5 are exact binary values: difference exactly 0.5
  EXPECT_EQ(types_of({rectangle(128, 64), rectangle(128, 64.5)}, {}, half).type,
            (std::vector<int>{0, 0}));
}

TEST(PanelTypes, CornerCountAndFoldAngleSeparateTypes) {
  const Outline sq = rectangle(200, 200);
  const Outline with_mid = {{0, 0}, {100, 0}, {200, 0}, {200, 200}, {0, 200}};
  const PanelTypes r = types_of({sq, with_mid, sq, sq, sq}, {0.0, 0.0, 0.4, 0.6, std::nan("")});
  // fold 0.4 is within 0.5 deg of 0; 0.6 is not; a NaN fold is never "farther
  // than the tolerance", so it joins the first square.
  EXPECT_EQ(r.type, (std::vector<int>{0, 1, 0, 2, 0}));
}

TEST(PanelTypes, CornerAnglesMustAgree) {
  // Same edge lengths, different angles: a square and a rhombus.
  const Outline rhombus = {{0, 0},
                           {200, 0},
                           {200 + 200 * std::cos(1.2), 200 * std::sin(1.2)},
                           {200 * std::cos(1.2), 200 * std::sin(1.2)}};
  EXPECT_EQ(types_of({rectangle(200, 200), rhombus}).type, (std::vector<int>{0, 1}));
}

TEST(PanelTypes, UnusableOutlinesMatchNothing) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Outline bad = {{0, 0}, {nan, 0}, {1, 1}};
  const PanelTypes r = types_of({bad, bad, Outline{}, Outline{}, rectangle(1, 1)});
  EXPECT_EQ(r.type, (std::vector<int>{0, 1, 2, 3, 4}));
}

TEST(PanelTypes, ManyTypesAcrossCellBoundaries) {
  // Rectangles 100 + 0.3 k wide: with tolerance 1 the greedy rule starts a
  // new type every 4th width (k = 0, 4, 8, ...: 1.2 > 1 from the last first
  // panel) whatever cells the widths fall in; shuffled order checked by the
  // definition: each panel's type is the first whose first panel is within 1.
  std::vector<Outline> outlines;
  for (int k = 0; k < 400; ++k) outlines.push_back(rectangle(100 + 0.3 * ((k * 37) % 400), 80));
  const PanelTypes r = types_of(outlines);
  for (std::size_t p = 0; p < outlines.size(); ++p) {
    const double w = outlines[p][1].x();
    int expect = -1;
    for (int t = 0; t < r.count() && expect < 0; ++t) {
      const double wt = outlines[static_cast<std::size_t>(r.representative[t])][1].x();
      if (std::abs(w - wt) <= 1.0 && static_cast<std::size_t>(r.representative[t]) <= p) expect = t;
    }
    if (expect < 0) expect = r.type[p];  // p starts a type: it must be that type's first panel
    ASSERT_EQ(r.type[p], expect) << p;
    ASSERT_LE(r.representative[r.type[p]], static_cast<int>(p));
  }
  for (int t = 1; t < r.count(); ++t) ASSERT_LT(r.representative[t - 1], r.representative[t]);
}

TEST(PanelTypes, RejectsBadParameters) {
  PanelTypeParams p;
  p.length_tol = -1.0;
  EXPECT_THROW(types_of({rectangle(1, 1)}, {}, p), InvalidParameter);
  p.length_tol = 1.0;  // one fold per outline
  EXPECT_THROW(panel_types(std::vector<Outline>{rectangle(1, 1)}, std::vector<double>{}, p),
               InvalidParameter);
}

TEST(PanelTypes, FoldAngleOfAnUnfoldedPanelIsItsLargestFold) {
  FlatPanel f;
  f.outline = rectangle(10, 10);
  EXPECT_EQ(type_fold_angle(f), 0.0);
  f.folds = {Fold{0, 2, 3.0}, Fold{1, 3, -7.5}};
  EXPECT_EQ(type_fold_angle(f), 7.5);
}
