// Diamond grids from two GSM guide-line sets (see the header).
#include "tessella/guide_line_diamond.h"

#include "tessella/curve_family_mesh.h"
#include "tessella/errors.h"
#include "tessella/guide_lines.h"
#include "tessella/surface_face.h"

namespace tessella {

PanelMesh guide_line_diamond(const SurfaceFace& face, const GuideLineDiamondParams& params) {
  require_in_range("rod_length (mm)", params.rod_length, 1e-3, 1e9);
  require_in_range("advance (mm)", params.advance, 0.0, 1e9);
  const double advance = params.advance > 0 ? params.advance : params.rod_length;
  GuideLineScalingParams gsm;
  // The GSM run's own chord division is not used (the nodes are the crossings
  // of the two sets); its rods set only its triangle mesh, which is dropped.
  gsm.rod_length = advance;
  gsm.advance = advance;
  gsm.finish_sweep = params.finish_sweep;
  gsm.guide_tolerance = params.guide_tolerance;
  gsm.max_curves = params.max_curves;
  gsm.trim_deflection = params.trim_deflection;
  gsm.max_panels = params.max_panels;
  std::vector<std::vector<SurfaceCurve>> families;
  for (const auto* guide : {&params.guide_a, &params.guide_b}) {
    gsm.guide = *guide;
    families.push_back(guide_line_scaling_curves(face, gsm).curves);
  }
  CurveFamilyMeshParams mp;
  mp.rod_length = advance;
  mp.triangulate = params.triangulate;
  mp.trim_deflection = params.trim_deflection;
  mp.max_panels = params.max_panels;
  return mesh_curve_families(face, families, mp);
}

}  // namespace tessella
