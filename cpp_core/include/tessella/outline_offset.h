// Offsetting a flat outline for the cutter (kerf / tool radius compensation).
#pragma once

#include <vector>

#include "tessella/vec.h"

namespace tessella {

struct OutlineOffsetParams {
  double distance = 0.0;     // mm, > 0 grows the outline (cut outside the part)
  double resolution = 1e-4;  // integer grid step of the computation (mm)
  // Corners: sharp (mitred, limited to 2x the distance, then squared) or round.
  bool round_corners = false;
  double arc_tolerance = 1e-3;  // mm, chord error of round corners
};

// The offset outline, counter-clockwise. Throws InvalidParameter if the
// outline vanishes (a negative distance larger than the part).
std::vector<Vec2> offset_outline(const std::vector<Vec2>& outline,
                                 const OutlineOffsetParams& params);

}  // namespace tessella
