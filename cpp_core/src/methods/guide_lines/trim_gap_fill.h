// Closing the narrow gaps a guide-line triangulation leaves along the trims
// (beyond seed 004), private to the guide-line methods.
#pragma once

#include <vector>

#include "methods/guide_lines/guide_curves.h"
#include "tessella/panel_mesh.h"

namespace tessella::guide_detail {

// Where the mesh's boundary leaves the trim between two of its nodes on the
// trim (A and B, on the same trim loop) and the strip between that stretch of
// the boundary and the trim is at most `max_width` wide (and over
// `min_width` somewhere), the strip is filled: nodes on the true trim about
// `cx.l1` apart and triangles between them and the mesh's boundary by the
// 90-degree rule. Curves that meet an edge at a glancing angle, or whose
// middle bows back from the far edge of the face, left such strips bare
// (0.3-1.1% of the British Museum roof, up to 1.5 m wide and 16 m long).
// A node is on the trim within `on_trim` (the loops' deflection and a
// little). Returns the number of strips filled.
int fill_trim_gaps(const Context& cx, const std::vector<TrimLoop>& loops, double on_trim,
                   double min_width, double max_width, PanelMesh& mesh);

}  // namespace tessella::guide_detail
