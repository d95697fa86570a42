// Panel classes (issue 16 part 3): how each panel is made from sheet.
//   flat:      its warp is within `flat_tolerance` (cut from flat sheet as it is);
//   cold-bent: within the cold-bending limit (cut flat, bent elastically on
//              site: the warp one corner takes out of the plane of the others);
//   curved:    beyond it (needs a mould: hot-bent glass, a formed sheet).
// Warp (mm): a quad of four vertices, the distance between its diagonals (the
// measure planarize() drives; a parallelogram's corners lie +-warp/2 off
// their mid-plane); any other panel, twice its vertices' largest distance from
// their least-squares plane (the same figure for a quad); a triangle, 0.
// The cold-bending limit is `cold_bend_warp` (mm) when set, else
// `cold_bend_ratio` x the panel's longest vertex-to-vertex distance. How
// far a pane may be cold-bent depends on its thickness, build-up and size
// (Datsiou & Overend 2016, "The mechanical response of cold bent monolithic
// glass plates during the bending process": distortion and snap-through set
// the limit before strength does); the 1% default is a placeholder for early
// design, to be replaced by the glass supplier's figure.
#pragma once

#include <array>
#include <vector>

#include "tessella/panel_mesh.h"

namespace tessella {

enum class PanelClass { Flat = 0, ColdBent = 1, Curved = 2 };

struct PanelClassParams {
  double flat_tolerance = 1.0;    // mm, > 0
  double cold_bend_ratio = 0.01;  // of the panel's longest diagonal, >= 0
  double cold_bend_warp = 0.0;    // mm; > 0 replaces the ratio
};

struct PanelClasses {
  std::vector<int> label;      // PanelClass per panel
  std::vector<double> warp;    // mm per panel
  std::vector<double> limit;   // mm, the panel's cold-bending limit
  std::array<int, 3> count{};  // flat, cold-bent, curved
};

// Each panel given by its vertices in order (outline points included).
// Throws InvalidParameter for a bad parameter.
PanelClasses classify_panels(const std::vector<std::vector<Vec3>>& panels,
                             const PanelClassParams& params = {});
PanelClasses classify_panels(const PanelMesh& mesh, const PanelClassParams& params = {});

// The warp of one panel's vertices (see above).
double panel_warp(const std::vector<Vec3>& points);

}  // namespace tessella
