// Grid lines that continue across the smooth edges between a face set's
// faces (issue 14): each face of a grid method spaces its lines over its own
// bounds, so on a roof in B-spline sub-surfaces of their own the rows broke
// at every cut (63% of the cut nodes carried a row on) and the join put the
// other face's nodes into the panels along the cut.
//
// Where an edge two faces share is an iso-line of both and they meet
// tangentially there (smooth_groups.h), the lines of one face that cross the
// edge are carried over into the other: the point where each meets the edge,
// found by the edge's own parameter (the same on both sides), gives the other
// face's line there. Faces are visited outwards from the largest (of each
// connected set of such edges); a face's lines in one direction are set once
// (by the first edge that reaches them, or as its own once they were carried
// over), so no line is asked of a face twice. Beyond the edge's span a face
// keeps its own lines.
#pragma once

#include <vector>

#include "faceset/face_set_impl.h"
#include "tessella/grid_methods.h"

namespace tessella {

// Per face of `set`, its grid lines with the edges' carried over (`own`:
// each face's own lines); `aligned` (if given): per face, whether any of
// its lines were carried over. `surface` (per face, its group of faces on
// one surface, -1: none; surface_groups.h): no lines are carried between
// faces of one surface, whose own lines already meet where they are
// spaced alike (97-100% of the split roof's rows), and carried ones spaced
// for the other face made the equal-size grid's rods vary more (+6.8%
// against the one face, +3.3% with their own).
std::vector<GridLines> align_grid_lines(const FaceSet::Impl& set, std::vector<GridLines> own,
                                        const std::vector<int>& surface,
                                        std::vector<char>* aligned = nullptr);

}  // namespace tessella
