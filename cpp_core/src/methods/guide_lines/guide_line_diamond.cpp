// Diamond grids from two GSM guide-line sets (see the header).
#include "tessella/guide_line_diamond.h"

#include <cmath>

#include "mesh/curve_family_mesh.h"
#include "methods/guide_lines/chord_division.h"
#include "methods/guide_lines/right_angle_rule.h"
#include "tessella/errors.h"
#include "tessella/guide_line_scaling.h"
#include "tessella/surface_face.h"
#include "tessella/two_guide_lines.h"

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
  gsm.ends_by_distance = params.ends_by_distance;
  gsm.guide_tolerance = params.guide_tolerance;
  gsm.max_curves = params.max_curves;
  gsm.trim_deflection = params.trim_deflection;
  gsm.max_panels = params.max_panels;
  std::vector<std::vector<SurfaceCurve>> families;
  std::vector<SurfaceCurve> guides;
  for (const auto* guide : {&params.guide_a, &params.guide_b}) {
    gsm.guide = *guide;
    GuideLineResult r = guide_line_scaling_curves(face, gsm);
    guides.push_back(r.curves[r.guide_index]);
    families.push_back(std::move(r.curves));
  }
  // Sets from (near) parallel guides are (near) parallel curves: no diamonds,
  // only the odd crossing where the sets bend. The guides need not cross
  // each other (their sets do), so the test is on their directions: chords
  // within 10 degrees of each other.
  const Vec3 ca = guides[0].xyz.back() - guides[0].xyz.front();
  const Vec3 cb = guides[1].xyz.back() - guides[1].xyz.front();
  if (std::abs(ca.normalized().dot(cb.normalized())) >
      std::cos(10.0 * 3.14159265358979323846 / 180.0))
    throw InvalidParameter(
        "guides: the two guide curves are (near) parallel, so their curve sets do not cross; "
        "pick guides that cross at an angle");
  CurveFamilyMeshParams mp;
  mp.rod_length = advance;
  mp.triangulate = params.triangulate;
  mp.trim_deflection = params.trim_deflection;
  mp.max_panels = params.max_panels;
  return mesh_curve_families(face, families, mp);
}

}  // namespace tessella
