// Lines of a tensor grid (increasing parameter values) made to run through
// given values: the cuts between faces of one surface that are iso-lines of
// it (issue 14), so a cut is a line of the layout instead of cutting its
// cells in two.
#pragma once

#include <vector>

namespace tessella {

// Each pinned value strictly inside (lines.front(), lines.back()) made a line:
// the nearest inner line moved onto it (by less than half its cell), or,
// where the nearest is a bound or was moved already, a line added.
void pin_lines(std::vector<double>& lines, std::vector<double> pinned);

// The lines that cover [lo, hi] (for a face inside the union the lines were
// made on): those strictly inside, after the last at or before lo and
// before the first at or after hi (lo / hi where there is none). The cells
// beyond the face's bounds are clipped away by its trims.
std::vector<double> lines_covering(const std::vector<double>& lines, double lo, double hi);

}  // namespace tessella
