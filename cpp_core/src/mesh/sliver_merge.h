// Merging panels too small to build into a neighbour: boundary slivers a trim
// cut off, and panels of (next to) no area that no method should return.
#pragma once

#include <vector>

#include "tessella/panel_mesh.h"

namespace tessella {

// Merges each panel p smaller than `fraction * reference_area[p]` into the
// neighbour it shares the longest edge with (reference_area[p] = 0: never).
// mesh.corner_uv, if filled, follows. Returns how many were merged.
int merge_slivers(PanelMesh& mesh, double fraction, const std::vector<double>& reference_area);

// A panel whose model area is below this share of the nominal panel area has
// no area a workshop could cut (collinear or repeated corners).
constexpr double kZeroAreaFraction = 1e-9;

// Merges every panel of (next to) zero area - under kZeroAreaFraction of
// mesh.nominal_area, or of model_size^2 x 1e-3 if the mesh has no nominal
// area - into a neighbour, and drops one that shares no edge with any (it
// covers nothing). Rods are rebuilt. Returns how many were merged or dropped.
int remove_zero_area_panels(PanelMesh& mesh, double model_size);

}  // namespace tessella
