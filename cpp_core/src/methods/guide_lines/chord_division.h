// Chord division of a polyline (seed 004 section 5.1 step 7), private to the
// guide-line methods.
#pragma once

#include <vector>

#include "tessella/vec.h"

namespace tessella {

// Equal-chord division of a polyline (seed 004 section 5.1 step 7). Returns the
// node positions as polyline parameters t (integer part = segment index,
// fraction = position on that segment); the first is 0 and the last is the end
// (points.size() - 1). Chords of `chord` (L1) are laid from the start; when the
// left-over chord L2 at the end is under merge_fraction * L1 it is merged into
// the last chord (the paper's rule), otherwise it is spread: the chord length is
// iterated (bisection) so that n equal chords end exactly at the end, with n the
// count (full chords, or one more) whose chord is closest to L1.
struct ChordDivisionParams {
  double chord = 0.0;           // L1 (mm), > 0
  double merge_fraction = 0.2;  // delta / L1
};
std::vector<double> divide_by_chords(const std::vector<Vec3>& points,
                                     const ChordDivisionParams& params);
// Chords of exactly `chord` laid from the start (at most max_count), as
// polyline parameters; the first is 0, the rest of the curve is left over.
std::vector<double> lay_chords(const std::vector<Vec3>& points, double chord, int max_count);
// Point of the polyline at parameter t (linear on each segment).
Vec3 polyline_point(const std::vector<Vec3>& points, double t);

}  // namespace tessella
