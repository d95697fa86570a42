// Panels from two crossing families of curves on a trimmed face (seed 004: the
// 2G2VM grid of section 6, and GSM's diamond grid from two guide-line sets,
// section 5.2.1). The cells between the curves are the quads; along the trim
// and around holes the curves end on the trim, and the cells there are closed
// by the trim itself (triangles, quads or pentagons with nodes where the curves
// meet the trim), so the grid covers the whole face instead of leaving open the
// cells whose fourth node would lie outside it.
//
// The cell structure is the planar curve network of the boundary-driven method
// (build_bd_network: nodes at crossings, curve ends on the trim and trim
// corners; faces by planar-graph traversal in (u,v)), followed by its
// short-edge collapse so that a curve meeting the trim next to a crossing or a
// corner does not leave a sliver.
#pragma once

#include <vector>

#include "methods/guide_lines/chord_division.h"
#include "methods/guide_lines/right_angle_rule.h"
#include "tessella/guide_line_scaling.h"
#include "tessella/panel_mesh.h"
#include "tessella/two_guide_lines.h"

namespace tessella {

class SurfaceFace;

struct CurveFamilyMeshParams {
  double rod_length = 0.0;  // nominal cell side (mm), > 0
  // Network edges shorter than this fraction of rod_length are collapsed.
  double min_edge_fraction = 0.3;
  // Split every quad along its shorter diagonal (3D) and fan larger boundary
  // cells into triangles.
  bool triangulate = false;
  double corner_angle = 30.0;    // deg: a sharper turn of a trim loop is a node
  double trim_deflection = 0.0;  // chord deflection of the trim polylines; 0 = automatic
  int max_panels = kDefaultMaxPanels;
};

// `families`: the curves of each family (any number of families; curves may
// run outside the face, they are cut at the trim). Returns the mesh with rods
// built; trim nodes lie exactly on the trim curves.
PanelMesh mesh_curve_families(const SurfaceFace& face,
                              const std::vector<std::vector<SurfaceCurve>>& families,
                              const CurveFamilyMeshParams& params);

}  // namespace tessella
