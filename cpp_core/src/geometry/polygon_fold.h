// Whether a polygon folds back on itself: a side that doubles back along the
// one before, or two sides on one line that overlap. Such an outline encloses
// no area where it folds, so a coverage measured by area does not see it.
// Exact orientation signs (no tolerance): corners along a straight trim in
// (u,v) lie exactly on its line.
#pragma once

#include <vector>

#include "tessella/vec.h"

namespace tessella {

bool folds_back_on_itself(const std::vector<Vec2>& p);

}  // namespace tessella
