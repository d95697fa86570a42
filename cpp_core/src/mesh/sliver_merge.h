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

// Merges each panel whose outline has a corner under `min_corner_deg` (3D)
// at a side that is a rod (node to node) into the neighbour across that rod,
// where the union has at most `max_nodes` nodes and its own sharpest corner
// is blunter than the panel's. The spike is a grid line (or an agent's row)
// meeting an opening's rim nearly along it: a panel tapering to a knife edge,
// no part a workshop can cut (iso_grid on trimmed_bspline_holes at 1200 mm:
// a rod leaving its trim node at 0.03 deg to the rim). In index order; rods
// are rebuilt. Returns how many were merged.
int merge_spikes(PanelMesh& mesh, double min_corner_deg, int max_nodes);

// The corner under which a panel's outline is a knife edge (deg).
constexpr double kSpikeCornerDeg = 5.0;

// A panel whose model area is below this share of the nominal panel area has
// no area a workshop could cut (collinear or repeated corners).
constexpr double kZeroAreaFraction = 1e-9;

// Merges every panel of (next to) zero area - under kZeroAreaFraction of
// mesh.nominal_area, or of model_size^2 x 1e-3 if the mesh has no nominal
// area - into a neighbour, and drops one that shares no edge with any (it
// covers nothing). Rods are rebuilt. Returns how many were merged or dropped.
int remove_zero_area_panels(PanelMesh& mesh, double model_size);

}  // namespace tessella
