// Guide-line grids for free-form grid shells (seed 004, section 5): the Guide
// Line Scaling Method (GSM). Its building blocks (chord division with the
// left-over rule, the 90-degree connection rule) are private to
// src/methods/guide_lines/.
#pragma once

#include <cstddef>
#include <vector>

#include "tessella/panel_mesh.h"
#include "tessella/vec.h"

namespace tessella {

class SurfaceFace;

// A curve lying on the surface: a dense polyline in (u,v) and the surface
// points it maps to (xyz[i] == face.point(uv[i])).
struct SurfaceCurve {
  std::vector<Vec2> uv;
  std::vector<Vec3> xyz;
};

// The Guide Line Scaling Method (seed 004 section 5). The guide is a 3D polyline
// on or near the face (the console API discretizes the user's edge).
struct GuideLineScalingParams {
  std::vector<Vec3> guide;      // >= 2 points, within guide_tolerance of the face
  double rod_length = 0.0;      // L1 (mm): target chord of the rods along the curves
  double advance = 0.0;         // L (mm): step between curves; 0 = rod_length * sqrt(3)/2
  double merge_fraction = 0.2;  // left-over rule: merge the rest under this * L1
  // Largest allowed distance of a guide point from the surface (mm);
  // 0 = 5% of the model size.
  double guide_tolerance = 0.0;
  int max_curves = 2000;  // refuse to advance more curves than this
  // After the GSM step stalls (the ends reached the far corners), offset the
  // curve point by point until it has left the face (covers the strip the
  // paper's sweep leaves open); false = the paper's sweep only.
  bool finish_sweep = true;
  // A new curve's ends: the boundary points `advance` (3D distance) from the
  // curve; false = seed 004's rule, the boundary point nearest the line
  // through D' parallel to the curve (ill-conditioned where the face is steep
  // across its edge).
  bool ends_by_distance = true;
  // Nodes of each curve at the feet of the midpoints of the neighbouring
  // curve's rods (staggered rows, near-equal rods between the curves); false =
  // the paper's equal chords on every curve.
  bool stagger = true;
  double trim_deflection = 0.0;  // chord deflection of the trim polylines; 0 = automatic
  int max_panels = kDefaultMaxPanels;
};

// What the method produced besides the mesh: the advanced curves in sweep order
// (for plots and checks).
struct GuideLineResult {
  PanelMesh mesh;
  std::vector<SurfaceCurve> curves;
  std::size_t guide_index = 0;  // curves[guide_index] is the guide, projected and extended
};

GuideLineResult guide_line_scaling_curves(const SurfaceFace& face,
                                          const GuideLineScalingParams& params);
// The triangle mesh only (rods built).
PanelMesh guide_line_scaling(const SurfaceFace& face, const GuideLineScalingParams& params);

}  // namespace tessella
