// Boundary-driven quad-dominant meshing of a trimmed face (seed 001, Wang,
// Krishnamurti, Shimada 2014): the stages of bd_sources.h, bd_tensor.h,
// bd_curves.h, bd_network.h and bd_refine.h in a row.
#pragma once

#include <vector>

#include "tessella/bd_network.h"
#include "tessella/bd_refine.h"
#include "tessella/panel_mesh.h"

namespace tessella {

struct BoundaryDrivenParams {
  double size = 0.0;        // target panel edge length, mm (required)
  double rho = 2.0;         // IDW power of the BDTensor (eq. 2)
  double skew_ratio = 0.3;  // min/max corner angle under which a triangle is removed
  int smoothing_iterations = 10;
  // Split every panel by centre + edge midpoints (section 3.2). The curves are
  // then traced 2 * size apart so the final panels come out near `size`.
  bool quadrangulate = true;
  BdSourceParams sources;
  double trim_deflection = 0.0;  // mm; 0 = 2.5e-7 * model size
  double step_fraction = 0.1;    // tracing step / curve spacing
  double corner_angle_deg = 30.0;
  // Network edges shorter than this fraction of the curve spacing are collapsed.
  double min_edge_fraction = 0.35;
  // After smoothing, nodes of panels with a corner under this angle (deg) are
  // relocated to open it (improve_bd_angles); 0 switches the step off.
  double angle_target_deg = 30.0;
  int angle_passes = 30;
  int max_panels = 200000;
};

// Everything the stages produced (the curve network for display, the mesh).
struct BoundaryDrivenResult {
  std::vector<BdPolyline> boundary;
  std::vector<BdCurve> curves;
  BdNetwork network;  // the preliminary mesh (before refinement)
  int removed_triangles = 0;
  int collapsed_edges = 0;
  int angle_moves = 0;  // node moves made by improve_bd_angles
  PanelMesh mesh;
};

BoundaryDrivenResult boundary_driven_stages(const SurfaceFace& face,
                                            const BoundaryDrivenParams& params);

// The final mesh: panels counter-clockwise about the face normal, rods built,
// nominal_area = size^2.
PanelMesh boundary_driven(const SurfaceFace& face, const BoundaryDrivenParams& params);

}  // namespace tessella
