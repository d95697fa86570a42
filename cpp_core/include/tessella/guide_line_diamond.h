// Diamond (quad) grids from two guide-line sets (seed 004 section 5.2.1, Fig.
// 19-20): the Guide Line Scaling Method is run once per guide, and the cells
// between the two curve families are the panels (curve_family_mesh.h), closed
// by the trim along the outline and around holes.
#pragma once

#include <vector>

#include "tessella/panel_mesh.h"
#include "tessella/vec.h"

namespace tessella {

class SurfaceFace;

struct GuideLineDiamondParams {
  std::vector<Vec3> guide_a, guide_b;  // two crossing guides on or near the face
  // Nominal rod length (mm): with advance = 0 the curves of each set are this
  // far apart, so rods are rod_length / sin(crossing angle) long (squares for
  // guides at right angles).
  double rod_length = 0.0;
  double advance = 0.0;      // step between the curves of each set (mm); 0 = rod_length
  bool finish_sweep = true;  // as GuideLineScalingParams::finish_sweep
  // As GuideLineScalingParams::ends_by_distance, but off (and not a
  // declared parameter: the document's EndsByDistance property is GSM's):
  // the crossings of two sets are the cells, and on the Sun Valley funnel
  // (oblique guides) ends by distance gave rods of variance 1,369,340 mm^2
  // against 910,254 with the paper's rule (Chen Shan +-30 deg: 407,424 /
  // 388,717).
  bool ends_by_distance = false;
  bool triangulate = false;      // split every cell along its shorter diagonal
  double guide_tolerance = 0.0;  // as for GSM; 0 = 5% of the model size
  int max_curves = 2000;
  double trim_deflection = 0.0;
  int max_panels = kDefaultMaxPanels;
};

PanelMesh guide_line_diamond(const SurfaceFace& face, const GuideLineDiamondParams& params);

}  // namespace tessella
