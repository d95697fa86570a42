// A generator's (u,v) path that runs along the cuts of a face set (the
// lines a roof was cut along into faces of one surface, given again as the
// net's guides, each computed to its own tolerance) follows those cuts
// exactly where it comes within a hundredth of the rod of them: the net's
// rows are then the cuts, not a row a few millimetres beside a cut, grazing
// it where it ends.
#pragma once

#include <vector>

#include "tessella/surface_face.h"
#include "tessella/vec.h"

namespace tessella {

// The path resampled on its own (u,v) steps (no step over size / 16 on the
// surface), and each point within 0.01 * size (on the surface) of a cut
// segment it runs along (within 20 deg) moved onto that segment's nearest
// point. Away from the cuts the path keeps its shape. cuts: (u,v) polylines
// on the face's surface (closed: the last point joins the first).
// Deterministic.
std::vector<Vec2> path_along_cuts(const SurfaceFace& face, const std::vector<Vec2>& path,
                                  const std::vector<std::vector<Vec2>>& cuts, double size);

}  // namespace tessella
