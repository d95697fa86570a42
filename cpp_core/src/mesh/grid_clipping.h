// Cuts a tensor grid of (u,v) lines by the trimmed face: full cells stay quads,
// boundary cells become polygons that follow the trim loops; holes stay open.
#pragma once

#include <vector>

#include "mesh/sliver_merge.h"
#include "tessella/grid_methods.h"
#include "tessella/panel_mesh.h"

namespace tessella {

class SurfaceFace;

// u_lines and v_lines: strictly increasing, covering the face's uv bounds.
PanelMesh clip_grid(const SurfaceFace& face, const std::vector<double>& u_lines,
                    const std::vector<double>& v_lines, const GridClipParams& params);

}  // namespace tessella
