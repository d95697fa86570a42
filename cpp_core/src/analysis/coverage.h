// Coverage of a face by a panel mesh: the parts of the face that no panel
// covers (gaps), that two or more panels cover (overlaps) and panel area
// outside the trims, measured in (u,v) and weighted to surface area.
//
// Why in (u,v): every panel is the image of its (u,v) outline, so a tiling of
// the face is a tiling of its (u,v) region; there it can be measured exactly
// along scanlines, where a 3D test would need a tolerance for each panel's
// deviation. Scanlines run both ways (rows of constant v, then of constant u)
// so that a thin gap along one direction is still crossed by the other; along
// a scanline the gap and overlap intervals are exact (the panels' straight
// (u,v) edges), each weighted by the surface's area element |Su x Sv| at its
// middle. The 3D confirmation is model_area: the panels' own areas, which
// cannot exceed the covered surface area by more than their deviation band
// allows (a flat piece is never larger than the surface it stands for, up to
// deviation x perimeter).
#pragma once

#include <string>
#include <vector>

#include "tessella/panel_mesh.h"
#include "tessella/surface_face.h"

namespace tessella {

// The share of the face area a result may leave uncovered, or cover twice, or
// spill outside the trims (each): 0.1%, the "no gap, no overlap".
constexpr double kMaxCoverageError = 1e-3;

struct CoverageParams {
  // Scanlines per direction; 0 = automatic (4 per panel row, 256 to 4096).
  int rows = 0;
  // Trim polylines of the face region (chords within this deflection, mm);
  // 0 = the automatic trim deflection (geometry/trim_deflection.h).
  double trim_deflection = 0.0;
};

struct Coverage {
  // Surface areas (mm^2): no panel / each panel beyond the first / panels
  // outside the trims. The larger of the two scan directions.
  double gap = 0.0, overlap = 0.0, outside = 0.0;
  double face_area = 0.0;
  // The surface area the panels cover (face - gap + overlap + outside), and
  // the sum of the panel models' own 3D areas (PanelMetrics::area).
  double covered_area = 0.0, model_area = 0.0;
  // Largest single gap interval met by a scanline: its middle on the surface
  // and its length (mm), to say where the hole is.
  Vec3 widest_gap_at = Vec3::Zero();
  double widest_gap = 0.0;

  double gap_fraction() const { return face_area > 0 ? gap / face_area : 0.0; }
  double overlap_fraction() const { return face_area > 0 ? (overlap + outside) / face_area : 0.0; }
};

// Measures the coverage of `face` by `mesh` (panel outlines from
// panel_corner_uv). `panel_areas`: the panel models' 3D areas (for
// model_area; may be empty).
Coverage measure_coverage(const SurfaceFace& face, const PanelMesh& mesh,
                          const std::vector<double>& panel_areas,
                          const CoverageParams& params = {});

// What is wrong with the coverage, in words (empty if nothing is).
std::string coverage_message(const Coverage& c, const std::string& method);

// Throws GeometryFailure with a message a user can act on when the coverage
// breaks kMaxCoverageError (gap, or overlap + outside), or when the panels'
// 3D area exceeds the covered surface area by more than their deviation band
// (`deviation_band`, mm^2: sum of deviation x perimeter) plus the same share.
void check_coverage(const Coverage& c, double deviation_band, const std::string& method);

}  // namespace tessella
