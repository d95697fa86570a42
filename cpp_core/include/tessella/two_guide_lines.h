// The Two Guide Lines with Two End Vertices Method of seed 004 (section 6).
#pragma once

#include <vector>

#include "tessella/guide_line_scaling.h"
#include "tessella/panel_mesh.h"
#include "tessella/vec.h"

namespace tessella {

class SurfaceFace;

// The Two Guide Lines with Two End Vertices Method (seed 004 section 6): the
// outer boundary is split at corners into boundary curves; from each end of a
// guide the boundary curve is divided into chords of rod_length (both ways;
// past a corner, or past the half-way point to the other end, along the
// tangent: the paper's boundary extension where a vertex has no twin); the
// guide is moved through the k-th vertex pairs (steps 4-6 of section 5.1);
// the cells between the two families, closed by the trim along the outline and
// around holes, are the panels (curve_family_mesh.h): quads inside, boundary
// cells with nodes where the curves meet the trim (`triangulate`: triangles).
struct TwoGuideLinesParams {
  std::vector<Vec3> guide_a, guide_b;
  double rod_length = 0.0;  // chord of the boundary vertices (mm)
  // > 0: every boundary curve at a guide end is divided into this many equal
  // chords instead (the paper's "divided in 48 segments"; each boundary curve
  // gets its own chord); 0 = chords of rod_length.
  int boundary_divisions = 0;
  bool triangulate = false;  // one diagonal per quad (the shorter)
  // Each curve is the guide moved through a vertex pair: by a similarity of
  // the (u,v) plane (true), or by the paper's 3D scale / rotate / nearest-point
  // projection (false; bows the curves on domes, see two_guide_lines.cpp).
  bool map_in_uv = true;
  double corner_angle = 30.0;    // deg: a sharper turn of the outline splits boundary curves
  double guide_tolerance = 0.0;  // as for GSM; 0 = 5% of the model size
  int max_curves = 2000;
  double trim_deflection = 0.0;
  int max_panels = kDefaultMaxPanels;
};
struct TwoGuideLinesResult {
  PanelMesh mesh;
  std::vector<SurfaceCurve> curves_a, curves_b;
};
TwoGuideLinesResult two_guide_lines_curves(const SurfaceFace& face,
                                           const TwoGuideLinesParams& params);
PanelMesh two_guide_lines(const SurfaceFace& face, const TwoGuideLinesParams& params);

}  // namespace tessella
