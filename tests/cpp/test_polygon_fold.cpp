// geometry/polygon_fold.h: outlines that fold back on themselves (zero area
// where they fold, unseen by an area-based coverage).
#include <gtest/gtest.h>

#include "geometry/polygon_fold.h"

namespace tessella {
namespace {

TEST(PolygonFold, AnOrdinaryPolygonDoesNotFold) {
  EXPECT_FALSE(folds_back_on_itself({{0, 0}, {2, 0}, {2, 1}, {0, 1}}));
  // Corners along a straight trim, running on in one direction.
  EXPECT_FALSE(folds_back_on_itself({{0, 0}, {1, 0}, {2, 0}, {3, 0}, {3, 1}, {0, 1}}));
  // Two collinear sides that only meet end to end (a notch's two rims).
  EXPECT_FALSE(
      folds_back_on_itself({{0, 0}, {1, 0}, {1, 1}, {2, 1}, {2, 0}, {3, 0}, {3, 2}, {0, 2}}));
}

TEST(PolygonFold, ASideDoublingBackFolds) {
  // Along the rim to 4, back to 2, then up: 747's top panel in small.
  EXPECT_TRUE(folds_back_on_itself({{0, 0}, {4, 0}, {2, 0}, {2, 1}, {0, 1}}));
}

TEST(PolygonFold, TwoSidesOverlappingOnALineFold) {
  // Along the rim 0 -> 3, up, back along the rim from 4 to 1 (non-adjacent
  // sides on y = 0 sharing [1, 3]).
  EXPECT_TRUE(
      folds_back_on_itself({{0, 0}, {3, 0}, {3, -1}, {4, -1}, {4, 0}, {1, 0}, {1, 2}, {0, 2}}));
}

TEST(PolygonFold, ACrossingIsNoFold) {
  // A bow tie crosses itself but encloses area on both sides (the coverage
  // sees it as an overlap): not this check's business.
  EXPECT_FALSE(folds_back_on_itself({{0, 0}, {2, 2}, {2, 0}, {0, 2}}));
}

}  // namespace
}  // namespace tessella
