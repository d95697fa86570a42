// Guide curves that run along the trims of a face set's faces (a roof cut
// along the very lines a designer then gives as the net's guides, each
// drawn or computed to its own tolerance) follow those trims exactly where
// they come within a hundredth of the rod: the net's rows are then the cuts,
// and no row runs a few millimetres beside a cut, grazing it.
#pragma once

#include <vector>

#include "tessella/methods.h"
#include "tessella/surface_face.h"

namespace tessella {

// Each guide resampled to points at most size / 16 apart; a point within
// 0.01 * size of a trim polyline of one of `faces` (at the deflection their
// cut uses: `trim_deflection` as GridClipParams) moves onto its nearest
// point there. Deterministic (segments in order; the first nearest wins).
Polylines guides_along_cuts(const std::vector<const SurfaceFace*>& faces, const Polylines& guides,
                            double size, double trim_deflection);

}  // namespace tessella
