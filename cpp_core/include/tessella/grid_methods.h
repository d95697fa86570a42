// The two foundation methods: grids of iso-parameter lines, cut by the trim
// boundary. Both return a PanelMesh with rods built and slivers merged.
#pragma once

#include <vector>

#include "tessella/methods.h"
#include "tessella/panel_mesh.h"

namespace tessella {

class SurfaceFace;

// What every grid method shares: how the grid is cut by the trim boundary.
struct GridClipParams {
  // Boundary panels whose area is under this fraction of a full panel are
  // merged into their neighbour.
  double sliver_fraction = 0.25;
  // Chord deflection of the trim polylines, mm. 0 = model_size * 1e-6, so every
  // boundary node lies within 1e-6 of the model size of the true trim curve.
  double trim_deflection = 0.0;
  // Refuse grids with more panels than this.
  int max_panels = kDefaultMaxPanels;
};

// Uniform in u and v: by counts (u_count, v_count > 0), or, when size > 0, by a
// target panel edge size in mm (counts from the mean iso-curve lengths).
struct IsoGridParams {
  int u_count = 0;
  int v_count = 0;
  double size = 0.0;
  GridClipParams clip;
};
PanelMesh iso_grid(const SurfaceFace& face, const IsoGridParams& params);

// Grid lines spaced by arc length (seed 001, Figure 3 right) so panel edges come
// out near `size` mm where the parameterization is uneven.
struct EqualSizeGridParams {
  double size = 0.0;  // required, mm
  GridClipParams clip;
};
PanelMesh equal_size_grid(const SurfaceFace& face, const EqualSizeGridParams& params);

// The grids' lines (increasing, from the face's bounds' minimum to their
// maximum), before the trim cut, and a grid of given lines cut by the trims
// as both grids cut theirs: a face set continues a grid's lines across the
// smooth edges between its faces on different surfaces (issue 14).
struct GridLines {
  std::vector<double> u, v;
};
GridLines iso_grid_lines(const SurfaceFace& face, const IsoGridParams& params);
GridLines equal_size_grid_lines(const SurfaceFace& face, const EqualSizeGridParams& params);
PanelMesh grid_on_lines(const SurfaceFace& face, const GridLines& lines,
                        const GridClipParams& clip);

// Parameters from values as the method declarations read them (checked).
IsoGridParams iso_grid_params(const ParamValues& values);
EqualSizeGridParams equal_size_grid_params(const ParamValues& values);

}  // namespace tessella
