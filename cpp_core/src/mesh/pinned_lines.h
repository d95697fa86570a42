// Lines of a tensor grid (increasing parameter values): made to run through
// given values (the cuts between faces of one surface that are iso-lines of
// it, issue 14, so a cut is a line of the layout instead of cutting its
// cells in two), taken for a face inside the union they were made on, and
// tidied into strictly increasing lines between two bounds.
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

// `sorted` (increasing, not empty) without values within 1e-9 x (hi - lo) of
// the one before, the first put on lo and the last on hi (hi added where the
// last is farther from it).
std::vector<double> increasing_lines(const std::vector<double>& sorted, double lo, double hi);

}  // namespace tessella
