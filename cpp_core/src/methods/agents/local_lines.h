// Lines that stop where the surface no longer needs them (issue 18 part 2).
// The walking agent's lines run across the whole face (a tensor grid): a line
// placed for one curved region densifies every flat region it crosses. This
// stage merges neighbouring whole cells of such a grid, two rectangles of
// cells sharing a full side at a time, wherever the merged panel (and every
// neighbour whose outline loses a node by it) still holds the bound: a line
// then stops at the last cell that needs it. Its end node stays a corner of
// the panels on both sides (a panel there has five or six corners, two of
// them on one straight side), so there is no T-junction: every node on a
// panel's side is a corner of that panel.
#pragma once

#include <functional>
#include <utility>
#include <vector>

#include "tessella/panel_mesh.h"

namespace tessella::agents {

// Whether a panel outline (3D corners and their (u,v)) holds the bound;
// `longest_side`: the longest of its four sides, each the length of the
// chords along it (a side with a line's end node on it is two chords).
using OutlineCheck =
    std::function<bool(const std::vector<Vec3>&, const std::vector<Vec2>&, double longest_side)>;

// Merges whole cells of `mesh`, the grid of `u_lines` x `v_lines` cut by the
// trims (clip_grid's panels, before folds). Only unfolded quads whose four
// corners are grid points are merged; every other panel stays as it is and
// keeps its corners as nodes. `folds` (panel index, diagonal) are renumbered
// to the new panel order; vertices no panel uses any more are removed.
// Deterministic. Returns the number of merges.
int stop_lines_early(PanelMesh& mesh, const std::vector<double>& u_lines,
                     const std::vector<double>& v_lines,
                     std::vector<std::pair<std::size_t, int>>& folds, const OutlineCheck& holds,
                     int max_corners = 5);

}  // namespace tessella::agents
